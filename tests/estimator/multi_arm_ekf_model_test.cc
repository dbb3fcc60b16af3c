// The N-arm EKF's process model (estimator/multi_arm_ekf_model.h): the free
// body's arm rows do not depend on the body pose and velocity, the Jacobian
// and the accelerometer's gradient against central differences, and the
// fourth-order transition against a matrix exponential by many small steps;
// the kernels of the prediction (the level arms' directions, the small-angle
// sincos, f(x, u) and the block covariance propagation) against the dense
// reference computations.
#include "estimator/multi_arm_ekf_model.h"

#include <gtest/gtest.h>

#include <random>

#include "estimator/multi_arm_ekf_jets.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

VehicleDescription Trirotor() {
  return LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml");
}

// A state near hover with the arms swinging and the rotors off their hover speed.
MultiArmEkfModel<3>::State SwingingState(const MultiArmEkfModel<3>& model) {
  using L = MultiArmEkfLayout<3>;
  const HoverSolution hover = SolveHover(model.vehicle());
  MultiArmEkfModel<3>::State x = MultiArmEkfModel<3>::State::Zero();
  x(L::kPitchRate) = 0.3;
  for (int i = 0; i < 3; ++i) {
    x(L::Deflection(i)) = 1.2e-3 + 2e-4 * i;
    x(L::DeflectionRate(i)) = 0.05 * (i - 1);
    x(L::Omega(i)) = hover.omega_rad_s[static_cast<size_t>(i)] + 20.0 * i;
    x(L::ThrustScale(i)) = 1.0 - 0.05 * i;
    x(L::GaugeOffset(i)) = 1e-5;
  }
  return x;
}

// Rotor speed commands 600, 650, 700 rad/s: each rotor off the others.
MultiArmEkfModel<3>::Input UnevenCommand() {
  MultiArmEkfModel<3>::Input u;
  for (int i = 0; i < 3; ++i) u.omega_cmd_rad_s[static_cast<size_t>(i)] = 600.0 + 50.0 * i;
  return u;
}

// Uniform gravity and a free body: (phi_ddot, b_ddot_i) of MultiArmAcceleration
// at random phi, x, z, x_dot, z_dot equal those at phi = 0 and rest (the
// model's evaluation point) to round-off (asserted 1e-12 rad/s^2, as the
// birotor's FreeArmDerivative test).
TEST(MultiArmEkfModelTest, FreeBodyArmRowsDoNotDependOnPoseOrBodyVelocity) {
  const VehicleDescription vehicle = Trirotor();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = CoordinateCount(vehicle);
  for (int trial = 0; trial < 50; ++trial) {
    MultiCoords<double> q = MultiCoords<double>::Zero(n), v = MultiCoords<double>::Zero(n);
    ArmForces<double> f(3);
    for (int i = 0; i < 3; ++i) {
      q(DeflectionIndex(i)) = 2e-3 * u(rng);
      v(DeflectionIndex(i)) = 0.5 * u(rng);
      f(i) = 15.0 + 10.0 * u(rng);
    }
    v(kPhi) = 2.0 * u(rng);
    const MultiCoords<double> reference = MultiArmAcceleration<double>(vehicle, q, v, f);
    MultiCoords<double> q_moved = q, v_moved = v;
    q_moved(kX) = 10.0 * u(rng);
    q_moved(kZ) = 10.0 * u(rng);
    q_moved(kPhi) = 3.0 * u(rng);
    v_moved(kX) = 5.0 * u(rng);
    v_moved(kZ) = 5.0 * u(rng);
    const MultiCoords<double> moved = MultiArmAcceleration<double>(vehicle, q_moved, v_moved, f);
    EXPECT_NEAR(moved(kPhi), reference(kPhi), 1e-12) << trial;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(moved(DeflectionIndex(i)), reference(DeflectionIndex(i)), 1e-12) << trial;
  }
}

// A_d and the accelerometer gradient against central differences of the
// derivative and of the specific force (step 1e-6 relative: truncation and
// round-off ~1e-9 of the column's scale; asserted 1e-6).
TEST(MultiArmEkfModelTest, JacobianMatchesCentralDifferences) {
  using Model = MultiArmEkfModel<3>;
  const Model model(Trirotor());
  const Model::State x = SwingingState(model);
  const Model::Input u = UnevenCommand();
  using L = MultiArmEkfLayout<3>;
  MultiArmAccelLinearization<3> accel;
  const Model::DynamicMatrix a = model.Jacobian(x, u, &accel);
  for (int c = 0; c < Model::kS; ++c) {
    const double h = 1e-6 * std::max(1.0, std::abs(x(c)));
    Model::State plus = x, minus = x;
    plus(c) += h;
    minus(c) -= h;
    const Model::State numeric = (model.Derivative(plus, u) - model.Derivative(minus, u)) / (2.0 * h);
    MultiArmAccelLinearization<3> at_plus, at_minus;
    model.Jacobian(plus, u, &at_plus);
    model.Jacobian(minus, u, &at_minus);
    const Eigen::Vector2d numeric_accel = (at_plus.value - at_minus.value) / (2.0 * h);
    const double scale = std::max(1.0, numeric.cwiseAbs().maxCoeff());
    for (int r = L::kFirstDynamic; r < Model::kS; ++r) {
      // The offsets (before kFirstDynamic) have no dynamics and move none.
      const double analytic = c >= L::kFirstDynamic ? a(L::Dynamic(r), L::Dynamic(c)) : 0.0;
      EXPECT_NEAR(analytic, numeric(r), 1e-6 * scale) << "row " << r << " col " << c;
    }
    for (int r = 0; r < 2; ++r) {
      EXPECT_NEAR(accel.jacobian(r, c), numeric_accel(r), 1e-6 * std::max(1.0, numeric_accel.cwiseAbs().maxCoeff()))
          << "accel row " << r << " col " << c;
    }
  }
}

// Phi = exp(A dt) to fourth order at dt = 1 ms against 1000 Euler-free steps
// of the same series at dt / 1000 multiplied out (the exponential to ~1e-12).
// Truncation ~(A dt)^5 / 120: measured 5.0e-4 of the largest entry (198),
// asserted 1e-3 (ratio 2: the truncation is a bound, not a noise figure).
TEST(MultiArmEkfModelTest, TransitionIsTheFourthOrderExponential) {
  using Model = MultiArmEkfModel<3>;
  const Model model(Trirotor());
  const Model::State x = SwingingState(model);
  const Model::DynamicMatrix a = model.Jacobian(x, Model::Input{});
  const double dt = 1e-3;
  const Model::DynamicMatrix small = Model::Transition(a, dt / 1000.0);
  Model::DynamicMatrix exact = Model::DynamicMatrix::Identity();
  for (int k = 0; k < 1000; ++k) exact = (small * exact).eval();
  const Model::DynamicMatrix phi = Model::Transition(a, dt);
  const double relative = (phi - exact).cwiseAbs().maxCoeff() / exact.cwiseAbs().maxCoeff();
  EXPECT_LT(relative, 1e-3);
  // The motor lag row is exact: exp(-dt / tau) to fourth order.
  using L = MultiArmEkfLayout<3>;
  // The motor lag entry: exp(-x) to fourth order, x = dt / tau = 0.0286, truncation x^5 / 120 = 1.6e-10.
  EXPECT_NEAR(phi(L::Dynamic(L::Omega(0)), L::Dynamic(L::Omega(0))), std::exp(-dt / 0.035), 2.4e-10);
}

// SinCos of a double within kSmallAngleRad (the Taylor series) against the
// library's sin and cos: a few 1e-17, asserted 4e-16 (2 ulp at 1, the
// rounding of either side); beyond it the library's own (exact match).
TEST(MultiArmEkfModelTest, SmallAngleSinCosIsTheLibrarysToRounding) {
  for (int k = -1000; k <= 1000; ++k) {
    const double x = kSmallAngleRad * k / 1000.0;
    double s = 0.0, c = 0.0;
    SinCos(x, &s, &c);
    EXPECT_NEAR(s, std::sin(x), 4e-16 * std::max(std::abs(x), 1e-300)) << x;
    EXPECT_NEAR(c, std::cos(x), 4e-16) << x;
  }
  for (const double x : {0.07, -0.5, 3.0}) {
    double s = 0.0, c = 0.0;
    SinCos(x, &s, &c);
    EXPECT_EQ(s, std::sin(x));
    EXPECT_EQ(c, std::cos(x));
  }
}

// LevelArmDirections (one sincos and the angle sums) against
// MultiArmDirections (the simulator's sin and cos of a_i + alpha_i, a_i +
// theta_i) at phi = 0 on every trirotor arm, values and, on Jets, derivatives
// to 1e-15 (rounding of unit vectors), the lever exactly.
TEST(MultiArmEkfModelTest, LevelArmDirectionsAreTheDenseOnes) {
  const VehicleDescription vehicle = Trirotor();
  const LevelArmDirections<3> level(vehicle);
  for (int i = 0; i < 3; ++i) {
    const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
    for (const double b : {-0.2, -0.01, -1.3e-3, 0.0, 1.4e-3, 0.05, 0.3}) {
      const ArmDirections<double> fast = level.At(i, b), dense = MultiArmDirections<double>(arm, b);
      EXPECT_NEAR(fast.rx, dense.rx, 1e-15) << i << " " << b;
      EXPECT_NEAR(fast.rz, dense.rz, 1e-15) << i << " " << b;
      EXPECT_NEAR(fast.nx, dense.nx, 1e-15) << i << " " << b;
      EXPECT_NEAR(fast.nz, dense.nz, 1e-15) << i << " " << b;
      EXPECT_EQ(fast.lever_m, dense.lever_m);
      const ArmJet b_jet(b, kArmJetDeflection);
      const ArmDirections<ArmJet> fast_jet = level.At(i, b_jet);
      const ArmDirections<ArmJet> dense_jet = MultiArmDirections<ArmJet>(arm, b_jet + ArmJet(0.0));
      for (int v = 0; v < kArmJetSize; ++v) {
        EXPECT_NEAR(fast_jet.rx.v(v), dense_jet.rx.v(v), 1e-15);
        EXPECT_NEAR(fast_jet.rz.v(v), dense_jet.rz.v(v), 1e-15);
        EXPECT_NEAR(fast_jet.nx.v(v), dense_jet.nx.v(v), 1e-15);
        EXPECT_NEAR(fast_jet.nz.v(v), dense_jet.nz.v(v), 1e-15);
      }
      EXPECT_NEAR(fast_jet.rx.a, dense.rx, 1e-15);
    }
  }
}

// f(x, u) (LevelArmDirections, MassMatrixLdlt) against MultiArmAcceleration
// (the simulator's terms and SolveMultiArmMassMatrix) at phi = 0 and rest:
// phi_ddot and b_ddot_i to 1e-12 rad/s^2.
TEST(MultiArmEkfModelTest, DerivativeIsTheDenseAcceleration) {
  using Model = MultiArmEkfModel<3>;
  using L = MultiArmEkfLayout<3>;
  const Model model(Trirotor());
  const Model::State x = SwingingState(model);
  const int n = CoordinateCount(model.vehicle());
  MultiCoords<double> q = MultiCoords<double>::Zero(n), v = MultiCoords<double>::Zero(n);
  ArmForces<double> f(3);
  v(kPhi) = x(L::kPitchRate);
  for (int i = 0; i < 3; ++i) {
    q(DeflectionIndex(i)) = x(L::Deflection(i));
    v(DeflectionIndex(i)) = x(L::DeflectionRate(i));
    f(i) = model.Force(x, i);
  }
  const MultiCoords<double> reference = MultiArmAcceleration<double>(model.vehicle(), q, v, f);
  const Model::State x_dot = model.Derivative(x, Model::Input{});
  EXPECT_NEAR(x_dot(L::kPitchRate), reference(kPhi), 1e-12);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(x_dot(L::DeflectionRate(i)), reference(DeflectionIndex(i)), 1e-12);
}

// Transition on the blocks (contiguous F, G, e through the series) against
// the dense series I + A dt (I + A dt/2 (I + A dt/3 (I + A dt/4))) on the
// whole A: to 1e-12 of Phi's largest entry, the rotor rows' exact zeros kept.
TEST(MultiArmEkfModelTest, BlockTransitionIsTheDenseSeries) {
  using Model = MultiArmEkfModel<3>;
  const Model model(Trirotor());
  const Model::State x = SwingingState(model);
  const Model::Input u = UnevenCommand();
  const Model::DynamicMatrix a = model.Jacobian(x, u);
  const double dt = 1e-3;
  bool blocks = false;
  const Model::DynamicMatrix phi = Model::Transition(a, dt, &blocks);
  ASSERT_TRUE(blocks);
  const Model::DynamicMatrix identity = Model::DynamicMatrix::Identity();
  const Model::DynamicMatrix a_dt = a * dt;
  const Model::DynamicMatrix dense =
      identity + a_dt * (identity + a_dt / 2.0 * (identity + a_dt / 3.0 * (identity + a_dt / 4.0)));
  EXPECT_LT((phi - dense).cwiseAbs().maxCoeff(), 1e-12 * dense.cwiseAbs().maxCoeff());
  EXPECT_TRUE(Model::HasRotorBlockStructure(phi));
}

// Propagate on the blocks [F, G; 0, D] against the dense Phi P Phi^T, to
// 1e-12 of P's largest entry, and its result exactly symmetric (the filter
// no longer symmetrises P after it).
TEST(MultiArmEkfModelTest, BlockPropagationIsTheDenseProduct) {
  using Model = MultiArmEkfModel<3>;
  const Model model(Trirotor());
  const Model::State x = SwingingState(model);
  const Model::Input u = UnevenCommand();
  bool blocks = false;
  const Model::DynamicMatrix phi = Model::Transition(model.Jacobian(x, u), 1e-3, &blocks);
  ASSERT_TRUE(blocks);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Model::DynamicMatrix root;
  for (int r = 0; r < Model::kD; ++r) {
    for (int c = 0; c < Model::kD; ++c) root(r, c) = uniform(rng);
  }
  const Model::DynamicMatrix p = root * root.transpose();
  const Model::DynamicMatrix dense = phi * p * phi.transpose();
  const Model::DynamicMatrix fast = Model::Propagate(phi, p, true);
  EXPECT_LT((fast - dense).cwiseAbs().maxCoeff(), 1e-12 * dense.cwiseAbs().maxCoeff());
  EXPECT_TRUE(fast == fast.transpose());
}

}  // namespace
}  // namespace birotor
