// The EKF's process and measurement models: the gravity-cancellation fact that
// lets the filter drop x, z, phi; Jacobians against central differences; the
// fourth-order transition matrix against the RK4 step and the dense
// polynomial; the accelerometer model against the hover equilibrium.
#include "estimator/ekf_model.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <limits>
#include <random>
#include <utility>

#include "model/equilibrium.h"

namespace birotor {
namespace {

// Central-difference steps per state, in its unit, for the Jacobian checks.
constexpr double kStep[kEkfStateSize] = {1e-7, 1e-7, 1e-5, 1e-5, 1e-5, 1e-3, 1e-3,
                                         1e-6, 1e-6, 1e-7, 1e-7, 1e-6, 1e-6, 1e-6};

EkfState HoverLikeState(std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  EkfState x;
  x(kDeflection1) = -0.0019 + 0.002 * u(*rng);
  x(kDeflection2) = 0.0019 + 0.002 * u(*rng);
  x(kPitchRate) = 0.5 * u(*rng);
  x(kDeflectionRate1) = 0.05 * u(*rng);
  x(kDeflectionRate2) = 0.05 * u(*rng);
  x(kOmega1) = 700.0 + 100.0 * u(*rng);
  x(kOmega2) = 700.0 + 100.0 * u(*rng);
  x(kThrustScale1) = 1.0 + 0.2 * u(*rng);
  x(kThrustScale2) = 1.0 + 0.2 * u(*rng);
  x(kGaugeOffset1) = 3e-5 * u(*rng);
  x(kGaugeOffset2) = 3e-5 * u(*rng);
  x(kStrainScale1) = 1.0 + 0.2 * u(*rng);
  x(kStrainScale2) = 1.0 + 0.2 * u(*rng);
  x(kBodyMassScale) = 1.0 + 0.2 * u(*rng);
  return x;
}

// The hover equilibrium (model/equilibrium.h) as a filter state, slow
// parameters at the file's values, and the command that holds it.
EkfState HoverState(const BirotorParams& p, EkfInput* u) {
  const Equilibrium eq = SolveHoverEquilibrium(p);
  EkfState x = EkfState::Zero();
  for (int i = 0; i < 2; ++i) {
    x(kDeflectionIndex[i]) = eq.deflection_rad[i];
    x(kOmegaIndex[i]) = eq.omega_rad_s[i];
    x(kThrustScaleIndex[i]) = 1.0;
    x(kStrainScaleIndex[i]) = 1.0;
    u->omega_cmd_rad_s[i] = eq.omega_rad_s[i];
  }
  x(kBodyMassScale) = 1.0;
  return x;
}

// With the body mass a state (the harder case: its column is not zero).
TEST(EkfProcessModelTest, JacobianMatchesCentralDifferences) {
  const BirotorParams p;
  const EkfProcessModel model(p, /*body_mass_is_state=*/true);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    const EkfState x = HoverLikeState(&rng);
    EkfInput u;
    u.omega_cmd_rad_s[0] = 650.0;
    u.omega_cmd_rad_s[1] = 1300.0;  // above omega_max: clamped, still differentiable in x
    // The slow states have no dynamics: A = [A_d, c; 0, 0], c the body mass's column.
    EkfMatrix a = EkfMatrix::Zero();
    DynamicVector mass_column;
    a.topLeftCorner<kDynamicStateSize, kDynamicStateSize>() = model.Jacobian(x, u, nullptr, &mass_column);
    a.block<kDynamicStateSize, 1>(0, kBodyMassScale) = mass_column;
    for (int j = 0; j < kEkfStateSize; ++j) {
      EkfState plus = x, minus = x;
      plus(j) += kStep[j];
      minus(j) -= kStep[j];
      const EkfState column = (model.Derivative(plus, u) - model.Derivative(minus, u)) / (2.0 * kStep[j]);
      for (int i = 0; i < kEkfStateSize; ++i) {
        EXPECT_NEAR(a(i, j), column(i), 1e-6 * (1.0 + std::abs(column(i)))) << "row " << i << " col " << j;
      }
    }
  }
}

// RK4 applied to a linear system is exactly the fourth-order Taylor
// polynomial of exp(A dt), so the derivative of one RK4 step matches Phi up to
// the (small) nonlinearity over one sample.
TEST(EkfProcessModelTest, TransitionMatchesTheDerivativeOfTheRk4Step) {
  const BirotorParams p;
  const EkfProcessModel model(p, /*body_mass_is_state=*/true);
  std::mt19937 rng(5);
  const double kFineStep[kEkfStateSize] = {1e-8, 1e-8, 1e-6, 1e-6, 1e-6, 1e-3, 1e-3,
                                           1e-6, 1e-6, 1e-8, 1e-8, 1e-6, 1e-6, 1e-6};
  const EkfState x = HoverLikeState(&rng);
  EkfInput u;
  // Rotors at their command: the rotor speed (and so df/dmu) is constant over the step.
  u.omega_cmd_rad_s[0] = x(kOmega1);
  u.omega_cmd_rad_s[1] = x(kOmega2);
  const double dt_s = 0.001;
  // The slow states are random walks: Phi = [Phi_d, Gamma; 0, I].
  EkfMatrix phi = EkfMatrix::Identity();
  DynamicVector mass_column;
  const DynamicMatrix a = model.Jacobian(x, u, nullptr, &mass_column);
  phi.topLeftCorner<kDynamicStateSize, kDynamicStateSize>() = EkfProcessModel::Transition(a, dt_s);
  phi.block<kDynamicStateSize, 1>(0, kBodyMassScale) = EkfProcessModel::ParameterTransition(a, mass_column, dt_s);
  for (int j = 0; j < kEkfStateSize; ++j) {
    EkfState plus = x, minus = x;
    plus(j) += kFineStep[j];
    minus(j) -= kFineStep[j];
    const EkfState column = (model.Step(plus, u, dt_s) - model.Step(minus, u, dt_s)) / (2.0 * kFineStep[j]);
    for (int i = 0; i < kEkfStateSize; ++i) {
      // The body mass's column (entries ~0.06) carries the change of its
      // coefficient c along the step of this moving state (b changes by a few
      // % of itself in 1 ms): 2.3 % measured on the arm rows, bound 1.5x that;
      // at rest it is 1e-4 (MassColumnMatchesTheRk4StepAtHover) and Gamma is
      // exact on a linear system (ParameterTransitionIsExactOnALinearSystem).
      const double tolerance =
          j == kBodyMassScale ? 3.5e-2 * std::abs(column(i)) + 1e-9 : 1e-4 * (1.0 + std::abs(column(i)));
      EXPECT_NEAR(phi(i, j), column(i), tolerance) << "row " << i << " col " << j;
    }
  }
}

// Transition works on the blocks of A = [A_aa, A_au; 0, D] (D diagonal):
// the same fourth-order polynomial as the dense products, to round-off, for
// the model's A in flight and on the ground, and (dense steps) for an A
// without that structure.
TEST(EkfProcessModelTest, TransitionIsTheFourthOrderPolynomial) {
  const EkfProcessModel model((BirotorParams()));
  std::mt19937 rng(23);
  const double dt_s = 0.001;
  const auto polynomial = [dt_s](const DynamicMatrix& a) {
    const DynamicMatrix a_dt = a * dt_s;
    const DynamicMatrix a2 = a_dt * a_dt, a3 = a2 * a_dt;
    return DynamicMatrix(DynamicMatrix::Identity() + a_dt + a2 / 2.0 + a3 / 6.0 + a3 * a_dt / 24.0);
  };
  EkfInput flying, supported;
  supported.body_supported = true;
  const EkfState x = HoverLikeState(&rng);
  DynamicMatrix dense = model.Jacobian(x, flying);
  dense(kOmega1, kDeflection1) = 10.0;  // not block triangular: the dense steps
  for (const DynamicMatrix& a : {model.Jacobian(x, flying), model.Jacobian(x, supported), dense}) {
    const DynamicMatrix expected = polynomial(a);
    const DynamicMatrix phi = EkfProcessModel::Transition(a, dt_s);
    // Round-off of the other summation order: 0.7-2.0e-16 of the largest
    // entry measured; 1e-15 for another build's vector width.
    EXPECT_LE((phi - expected).cwiseAbs().maxCoeff(), 1e-15 * expected.cwiseAbs().maxCoeff());
  }
  // The structure the fast path relies on holds for the model's A.
  constexpr int n = kOmega1, m = kDynamicStateSize - kOmega1;  // arm states; omega and mu
  for (const EkfInput& u : {flying, supported}) {
    const DynamicMatrix a = model.Jacobian(x, u);
    EXPECT_TRUE((a.bottomLeftCorner<m, n>().isZero(0.0)));
    EXPECT_TRUE((a.bottomRightCorner<m, m>().isDiagonal(0.0)));
  }
}

// The structure check is Eigen's bottomLeftCorner().isZero(0.0) &&
// bottomRightCorner().isDiagonal(0.0), case by case: exact and signed zeros,
// the smallest subnormal, NaN and infinities off and on D's diagonal.
TEST(EkfProcessModelTest, RotorBlockStructureMatchesEigensCheck) {
  constexpr int n = kOmega1, m = kDynamicStateSize - kOmega1;  // arm states; omega and mu
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const double tiny = std::numeric_limits<double>::denorm_min();
  auto eigen = [&](const DynamicMatrix& x) {
    return x.bottomLeftCorner<m, n>().isZero(0.0) && x.bottomRightCorner<m, m>().isDiagonal(0.0);
  };
  DynamicMatrix base = DynamicMatrix::Constant(2.0);  // arm rows dense
  base.bottomRows<m>().setZero();
  base.bottomRightCorner<m, m>().diagonal() << -40.0, -40.0, 0.0, 0.0;
  struct Case {
    int row, col;
    double value;
  };
  const Case cases[] = {{8, 0, 0.0}, {8, 0, -0.0}, {5, 3, tiny}, {6, 7, tiny}, {7, 6, -1e300}, {5, 0, nan},
                        {8, 8, nan}, {6, 6, inf},  {7, 7, -inf}, {5, 5, 0.0},  {0, 8, inf},    {2, 7, nan}};
  EXPECT_TRUE(EkfProcessModel::HasRotorBlockStructure(base));
  for (const Case& c : cases) {
    DynamicMatrix x = base;
    x(c.row, c.col) = c.value;
    EXPECT_EQ(EkfProcessModel::HasRotorBlockStructure(x), eigen(x)) << c.row << "," << c.col << " = " << c.value;
  }
  // Two off-diagonal entries whose |x| sum overflows stay non-zero.
  DynamicMatrix big = base;
  big(5, 0) = big(5, 1) = std::numeric_limits<double>::max();
  EXPECT_FALSE(EkfProcessModel::HasRotorBlockStructure(big));
  EXPECT_EQ(EkfProcessModel::HasRotorBlockStructure(big), eigen(big));
}

// At the hover equilibrium (x_dot = 0) the second-order terms vanish: the
// body mass's column of Phi is the derivative of the RK4 step.
TEST(EkfProcessModelTest, MassColumnMatchesTheRk4StepAtHover) {
  const BirotorParams p;
  const EkfProcessModel model(p, /*body_mass_is_state=*/true);
  EkfInput u;
  const EkfState x = HoverState(p, &u);
  const double dt_s = 0.001, step = 1e-6;
  DynamicVector column;
  const DynamicVector gamma =
      EkfProcessModel::ParameterTransition(model.Jacobian(x, u, nullptr, &column), column, dt_s);
  EkfState plus = x, minus = x;
  plus(kBodyMassScale) += step;
  minus(kBodyMassScale) -= step;
  const EkfState expected = (model.Step(plus, u, dt_s) - model.Step(minus, u, dt_s)) / (2.0 * step);
  // A heavier body under the same thrust: the arms bend up less (b1 up, b2 down).
  EXPECT_GT(std::abs(expected(kDeflectionRate1)), 0.01);
  for (int i = 0; i < kDynamicStateSize; ++i) {
    EXPECT_NEAR(gamma(i), expected(i), 1e-4 * std::abs(expected(i)) + 1e-9) << "row " << i;
  }
}

// x_dot = A x + c p with p constant: one RK4 step is x + (Phi - I) x + Gamma p
// with Phi and Gamma the fourth-order Taylor polynomials, so d x+ / d p =
// Gamma to round-off.
TEST(EkfProcessModelTest, ParameterTransitionIsExactOnALinearSystem) {
  std::mt19937 rng(29);
  std::normal_distribution<double> n(0.0, 1.0);
  DynamicMatrix a;
  DynamicVector c, x;
  for (int i = 0; i < kDynamicStateSize; ++i) {
    c(i) = n(rng);
    x(i) = n(rng);
    for (int j = 0; j < kDynamicStateSize; ++j) a(i, j) = 300.0 * n(rng);  // |A dt| ~ 1, as the arm modes
  }
  const double dt_s = 0.001;
  const auto step = [&](double p) {
    return Rk4Step(x, dt_s, [&](const DynamicVector& s) -> DynamicVector { return a * s + c * p; });
  };
  const DynamicVector gamma = EkfProcessModel::ParameterTransition(a, c, dt_s);
  const DynamicVector expected = step(1.0) - step(0.0);
  EXPECT_LE((gamma - expected).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + expected.cwiseAbs().maxCoeff()));
}

// Transition's Gamma, from its Horner factor W (Phi_d = I + A dt W, Gamma =
// W c dt), is ParameterTransition's polynomial to round-off: for a dense A
// and for the model's A in flight (the block path).
TEST(EkfProcessModelTest, TransitionsGammaIsParameterTransition) {
  std::mt19937 rng(31);
  std::normal_distribution<double> n(0.0, 1.0);
  DynamicMatrix dense;
  DynamicVector c;
  for (int i = 0; i < kDynamicStateSize; ++i) {
    c(i) = n(rng);
    for (int j = 0; j < kDynamicStateSize; ++j) dense(i, j) = 300.0 * n(rng);  // |A dt| ~ 1, as the arm modes
  }
  const BirotorParams p;
  const EkfProcessModel model(p, /*body_mass_is_state=*/true);
  EkfInput u;
  EkfState x = HoverState(p, &u);
  x(kDeflectionRate1) += 0.3;
  x(kOmega2) *= 1.1;
  DynamicVector mass_column;
  const DynamicMatrix flight = model.Jacobian(x, u, nullptr, &mass_column);
  ASSERT_TRUE(EkfProcessModel::HasRotorBlockStructure(flight));
  const double dt_s = 0.001;
  for (const auto& [a, column] : {std::make_pair(dense, c), std::make_pair(flight, mass_column)}) {
    DynamicVector gamma;
    const DynamicMatrix phi = EkfProcessModel::Transition(a, dt_s, &column, &gamma);
    EXPECT_EQ(phi, EkfProcessModel::Transition(a, dt_s));  // Gamma leaves Phi_d as it was, bit for bit
    const DynamicVector expected = EkfProcessModel::ParameterTransition(a, column, dt_s);
    EXPECT_LE((gamma - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
  }
}

TEST(EkfProcessModelTest, HoldsTheHoverEquilibrium) {
  const BirotorParams p;
  const EkfProcessModel model(p);
  EkfInput u;
  const EkfState x = HoverState(p, &u);
  const EkfState x_dot = model.Derivative(x, u);
  EXPECT_NEAR(x(kDeflection1), -0.0018664, 1e-6);
  EXPECT_LE(x_dot.cwiseAbs().maxCoeff(), 1e-6);
}

// The direct models read what their comment says (ekf_model.h): strain
// z_i = g_i b_i + e_i, telemetry omega_i, gyro phi_dot; for the last two
// h(x) = H x with H the selection, unchanged by a Linearize call (the model
// is const).
TEST(MeasurementModelTest, DirectModelsReadTheirStates) {
  std::mt19937 rng(11);
  const EkfState x = HoverLikeState(&rng);
  const StrainMeasurementModel strain(2e-5);
  const StrainMeasurementModel::Linearization s = strain.Linearize(x);
  for (int i = 0; i < 2; ++i) {
    const int b = kDeflectionIndex[i], e = kGaugeOffsetIndex[i], g = kStrainScaleIndex[i];
    EXPECT_EQ(s.predicted(i), x(g) * x(b) + x(e));
    for (int j = 0; j < kEkfStateSize; ++j) {
      const double expected = j == b ? x(g) : j == g ? x(b) : j == e ? 1.0 : 0.0;
      EXPECT_EQ(s.jacobian(i, j), expected) << "row " << i << " col " << j;
    }
  }
  EXPECT_DOUBLE_EQ(strain.noise(0, 0), 4e-10);
  const MotorSpeedMeasurementModel motor(5.0);
  const MotorSpeedMeasurementModel::Linearization m = motor.Linearize(x);
  EXPECT_EQ(m.predicted(0), x(kOmega1));
  EXPECT_EQ(m.predicted(1), x(kOmega2));
  EXPECT_EQ(m.jacobian.sum(), 2.0);
  EXPECT_EQ(motor.noise(1, 1), 25.0);
  const GyroMeasurementModel gyro(0.005);
  EXPECT_EQ(gyro.Linearize(x).predicted(0), x(kPitchRate));
  EXPECT_EQ(gyro.Linearize(x).jacobian(0, kPitchRate), 1.0);
  EXPECT_EQ(gyro.Linearize(x).jacobian.sum(), 1.0);
}

TEST(MeasurementModelTest, AccelerometerJacobianMatchesCentralDifferences) {
  const BirotorParams p;
  const EkfProcessModel process(p, /*body_mass_is_state=*/true);
  std::mt19937 rng(19);
  for (int trial = 0; trial < 5; ++trial) {
    const EkfState x = HoverLikeState(&rng);
    const AccelerometerMeasurementModel::Jacobian h = AccelerometerMeasurementModel::Linearize(process, x).jacobian;
    for (int j = 0; j < kEkfStateSize; ++j) {
      EkfState plus = x, minus = x;
      plus(j) += kStep[j];
      minus(j) -= kStep[j];
      const double column = (AccelerometerMeasurementModel::Linearize(process, plus).predicted(0) -
                             AccelerometerMeasurementModel::Linearize(process, minus).predicted(0)) /
                            (2.0 * kStep[j]);
      EXPECT_NEAR(h(0, j), column, 1e-6 * (1.0 + std::abs(column))) << "col " << j;
    }
  }
}

// The process Jacobian's by-product (the z row of the same solve) is the
// accelerometer model at x0, and to first order near it.
TEST(MeasurementModelTest, AccelerometerFromTheProcessJacobianMatchesTheDirectModel) {
  const BirotorParams p;
  const EkfProcessModel process(p, /*body_mass_is_state=*/true);
  std::mt19937 rng(23);
  for (int trial = 0; trial < 5; ++trial) {
    const EkfState x = HoverLikeState(&rng);
    EkfInput u;
    u.omega_cmd_rad_s[0] = u.omega_cmd_rad_s[1] = 700.0;
    AccelerometerLinearization at;
    process.Jacobian(x, u, &at);
    ASSERT_TRUE(at.valid);
    const AccelerometerMeasurementModel::Linearization direct = AccelerometerMeasurementModel::Linearize(process, x);
    const AccelerometerMeasurementModel::Linearization cached = AccelerometerMeasurementModel::Linearize(at, x);
    const double a_direct = direct.predicted(0);
    EXPECT_NEAR(cached.predicted(0), a_direct, 1e-9 * std::abs(a_direct));
    for (int j = 0; j < kEkfStateSize; ++j) {
      EXPECT_NEAR(cached.jacobian(0, j), direct.jacobian(0, j), 1e-9 * (1.0 + std::abs(direct.jacobian(0, j))));
    }
    // One millisecond of typical motion later: first order holds to 1e-3 m/s^2
    // (the accelerometer's noise is 0.05).
    const EkfState moved = process.Step(x, u, 0.001);
    EXPECT_NEAR(AccelerometerMeasurementModel::Linearize(at, moved).predicted(0),
                AccelerometerMeasurementModel::Linearize(process, moved).predicted(0), 1e-3);
  }
  EkfInput ground;
  ground.body_supported = true;
  AccelerometerLinearization at;
  process.Jacobian(HoverLikeState(&rng), ground, &at);
  EXPECT_FALSE(at.valid);
}

// At the hover equilibrium the arms are still: a_z = (f1 + f2) / (m + 2 m_p) = g,
// whatever the gauge offsets. The thrust reaches the body only through the
// hinge springs: a_z does not move with f_i at once (d a_z / d mu_i = 0) but
// with the deflections, d a_z / d b_i = -/+ k / (L m) (reference-vehicle.md:
// z_ddot = -k / (L m) b_d + ..., b_d = b1 - b2); the offsets do not enter.
TEST(MeasurementModelTest, AccelerometerReadsTheThrustThroughTheHinges) {
  const BirotorParams p;
  const EkfProcessModel process(p);
  EkfInput u;
  EkfState x = HoverState(p, &u);
  for (int i = 0; i < 2; ++i) x(kGaugeOffsetIndex[i]) = 1e-4;
  const AccelerometerMeasurementModel::Linearization model = AccelerometerMeasurementModel::Linearize(process, x);
  EXPECT_NEAR(model.predicted(0), p.gravity_m_s2, 1e-9);
  const double k_over_lm = p.arm_stiffness_n_m_rad / (p.arm_length_m * p.body_mass_kg);  // [m/s^2 per rad]
  EXPECT_NEAR(model.jacobian(0, kDeflection1), -k_over_lm, 0.01 * k_over_lm);
  EXPECT_NEAR(model.jacobian(0, kDeflection2), k_over_lm, 0.01 * k_over_lm);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(model.jacobian(0, kThrustScaleIndex[i]), 0.0, 1e-9);
    EXPECT_EQ(model.jacobian(0, kGaugeOffsetIndex[i]), 0.0);
  }
}

}  // namespace
}  // namespace birotor
