// The EKF's process and measurement models: the gravity-cancellation fact that
// lets the filter drop x, z, phi; Jacobians against central differences; the
// fourth-order transition matrix against the RK4 step; the accelerometer
// model against the hover equilibrium.
#include "estimator/ekf_model.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <random>

#include "model/equilibrium.h"

namespace birotor {
namespace {

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
  return x;
}

TEST(EkfProcessModelTest, JacobianMatchesCentralDifferences) {
  const VehicleParams p;
  const EkfProcessModel model(p);
  std::mt19937 rng(3);
  // Steps per state, in its unit.
  const double kStep[kEkfStateSize] = {1e-7, 1e-7, 1e-5, 1e-5, 1e-5, 1e-3, 1e-3, 1e-6, 1e-6, 1e-7, 1e-7};
  for (int trial = 0; trial < 10; ++trial) {
    const EkfState x = HoverLikeState(&rng);
    EkfInput u;
    u.omega_cmd_rad_s[0] = 650.0;
    u.omega_cmd_rad_s[1] = 1300.0;  // above omega_max: clamped, still differentiable in x
    // The offsets have no dynamics: A = blockdiag(A_d, 0).
    EkfMatrix a = EkfMatrix::Zero();
    a.topLeftCorner<kDynamicStateSize, kDynamicStateSize>() = model.Jacobian(x, u);
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
  const VehicleParams p;
  const EkfProcessModel model(p);
  std::mt19937 rng(5);
  const double kStep[kEkfStateSize] = {1e-8, 1e-8, 1e-6, 1e-6, 1e-6, 1e-3, 1e-3, 1e-6, 1e-6, 1e-8, 1e-8};
  const EkfState x = HoverLikeState(&rng);
  EkfInput u;
  // Rotors at their command: the rotor speed (and so df/dmu) is constant over the step.
  u.omega_cmd_rad_s[0] = x(kOmega1);
  u.omega_cmd_rad_s[1] = x(kOmega2);
  const double dt_s = 0.001;
  // The offsets are random walks: Phi = blockdiag(Phi_d, I).
  EkfMatrix phi = EkfMatrix::Identity();
  phi.topLeftCorner<kDynamicStateSize, kDynamicStateSize>() = EkfProcessModel::Transition(model.Jacobian(x, u), dt_s);
  for (int j = 0; j < kEkfStateSize; ++j) {
    EkfState plus = x, minus = x;
    plus(j) += kStep[j];
    minus(j) -= kStep[j];
    const EkfState column = (model.Step(plus, u, dt_s) - model.Step(minus, u, dt_s)) / (2.0 * kStep[j]);
    for (int i = 0; i < kEkfStateSize; ++i) {
      EXPECT_NEAR(phi(i, j), column(i), 1e-4 * (1.0 + std::abs(column(i)))) << "row " << i << " col " << j;
    }
  }
}

TEST(EkfProcessModelTest, HoldsTheHoverEquilibrium) {
  const VehicleParams p;
  const EkfProcessModel model(p);
  const Equilibrium eq = SolveHoverEquilibrium(p);
  EkfState x = EkfState::Zero();
  EkfInput u;
  for (int i = 0; i < 2; ++i) {
    x(kDeflectionIndex[i]) = eq.deflection_rad[i];
    x(kOmegaIndex[i]) = eq.omega_rad_s[i];
    x(kThrustScaleIndex[i]) = 1.0;
    u.omega_cmd_rad_s[i] = eq.omega_rad_s[i];
  }
  const EkfState x_dot = model.Derivative(x, u);
  EXPECT_NEAR(x(kDeflection1), -0.0018664, 1e-6);
  EXPECT_LE(x_dot.cwiseAbs().maxCoeff(), 1e-6);
}

template <typename Model>
void ExpectJacobianMatchesPredict(const Model& model) {
  std::mt19937 rng(11);
  const EkfState x = HoverLikeState(&rng);
  for (int j = 0; j < kEkfStateSize; ++j) {
    EkfState plus = x, minus = x;
    plus(j) += 1e-6;
    minus(j) -= 1e-6;
    const typename Model::Vector column = (Model::Predict(plus) - Model::Predict(minus)) / 2e-6;
    for (int i = 0; i < Model::kSize; ++i) EXPECT_NEAR(model.h_jacobian(i, j), column(i), 1e-6);
  }
}

TEST(MeasurementModelTest, JacobiansMatchCentralDifferences) {
  ExpectJacobianMatchesPredict(StrainMeasurementModel(2e-5));
  ExpectJacobianMatchesPredict(MotorSpeedMeasurementModel(5.0));
  ExpectJacobianMatchesPredict(GyroMeasurementModel(0.005));
}

TEST(MeasurementModelTest, AccelerometerJacobianMatchesCentralDifferences) {
  const VehicleParams p;
  const EkfProcessModel process(p);
  AccelerometerMeasurementModel model(0.05);
  std::mt19937 rng(19);
  const double kStep[kEkfStateSize] = {1e-7, 1e-7, 1e-5, 1e-5, 1e-5, 1e-3, 1e-3, 1e-6, 1e-6, 1e-7, 1e-7};
  for (int trial = 0; trial < 5; ++trial) {
    const EkfState x = HoverLikeState(&rng);
    model.Linearize(process, x);
    const AccelerometerMeasurementModel::Jacobian h = model.h_jacobian;
    for (int j = 0; j < kEkfStateSize; ++j) {
      EkfState plus = x, minus = x;
      plus(j) += kStep[j];
      minus(j) -= kStep[j];
      AccelerometerMeasurementModel scratch(0.05);
      const double column =
          (scratch.Linearize(process, plus)(0) - scratch.Linearize(process, minus)(0)) / (2.0 * kStep[j]);
      EXPECT_NEAR(h(0, j), column, 1e-6 * (1.0 + std::abs(column))) << "col " << j;
    }
  }
}

// The process Jacobian's by-product (the z row of the same solve) is the
// accelerometer model at x0, and to first order near it.
TEST(MeasurementModelTest, AccelerometerFromTheProcessJacobianMatchesTheDirectModel) {
  const VehicleParams p;
  const EkfProcessModel process(p);
  std::mt19937 rng(23);
  for (int trial = 0; trial < 5; ++trial) {
    const EkfState x = HoverLikeState(&rng);
    EkfInput u;
    u.omega_cmd_rad_s[0] = u.omega_cmd_rad_s[1] = 700.0;
    AccelerometerLinearization at;
    process.Jacobian(x, u, &at);
    ASSERT_TRUE(at.valid);
    AccelerometerMeasurementModel direct(0.05), cached(0.05);
    const double a_direct = direct.Linearize(process, x)(0);
    EXPECT_NEAR(cached.Linearize(at, x)(0), a_direct, 1e-9 * std::abs(a_direct));
    for (int j = 0; j < kEkfStateSize; ++j) {
      EXPECT_NEAR(cached.h_jacobian(0, j), direct.h_jacobian(0, j), 1e-9 * (1.0 + std::abs(direct.h_jacobian(0, j))));
    }
    // One millisecond of typical motion later: first order holds to 1e-3 m/s^2
    // (the accelerometer's noise is 0.05).
    const EkfState moved = process.Step(x, u, 0.001);
    EXPECT_NEAR(cached.Linearize(at, moved)(0), direct.Linearize(process, moved)(0), 1e-3);
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
  const VehicleParams p;
  const EkfProcessModel process(p);
  AccelerometerMeasurementModel model(0.05);
  const Equilibrium eq = SolveHoverEquilibrium(p);
  EkfState x = EkfState::Zero();
  for (int i = 0; i < 2; ++i) {
    x(kDeflectionIndex[i]) = eq.deflection_rad[i];
    x(kOmegaIndex[i]) = eq.omega_rad_s[i];
    x(kThrustScaleIndex[i]) = 1.0;
    x(kGaugeOffsetIndex[i]) = 1e-4;
  }
  EXPECT_NEAR(model.Linearize(process, x)(0), p.gravity_m_s2, 1e-9);
  const double k_over_lm = p.arm_stiffness_n_m_rad / (p.arm_length_m * p.body_mass_kg);  // [m/s^2 per rad]
  EXPECT_NEAR(model.h_jacobian(0, kDeflection1), -k_over_lm, 0.01 * k_over_lm);
  EXPECT_NEAR(model.h_jacobian(0, kDeflection2), k_over_lm, 0.01 * k_over_lm);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(model.h_jacobian(0, kThrustScaleIndex[i]), 0.0, 1e-9);
    EXPECT_EQ(model.h_jacobian(0, kGaugeOffsetIndex[i]), 0.0);
  }
}

// A badly scaled but valid covariance, as in the filter (b ~ 1e-5, omega ~ 10).
EkfMatrix RandomCovariance(std::mt19937* rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double kScale[kEkfStateSize] = {1e-5, 1e-5, 0.1, 0.01, 0.01, 10.0, 10.0, 0.1, 0.1, 1e-5, 1e-5};
  EkfMatrix root;
  for (int i = 0; i < kEkfStateSize; ++i) {
    for (int j = 0; j < kEkfStateSize; ++j) root(i, j) = n(*rng) * kScale[i];
  }
  return root * root.transpose();
}

// The textbook Joseph form, dense: (I - K H) P (I - K H)^T + K R K^T.
template <int M>
EkfMatrix TextbookJoseph(const EkfMatrix& p, const Eigen::Matrix<double, kEkfStateSize, M>& k,
                         const Eigen::Matrix<double, M, kEkfStateSize>& h, const Eigen::Matrix<double, M, M>& r) {
  const EkfMatrix i_kh = EkfMatrix::Identity() - k * h;
  return i_kh * p * i_kh.transpose() + k * r * k.transpose();
}

// With a gain that is NOT the Kalman gain the expanded form P - K S K^T is
// wrong; the Joseph form holds for any gain, so this is what tells them apart.
TEST(JosephCovarianceTest, MatchesTheTextbookFormForANonOptimalGain) {
  std::mt19937 rng(13);
  std::normal_distribution<double> n(0.0, 1.0);
  const StrainMeasurementModel strain(2e-5);
  const MotorSpeedMeasurementModel motor(5.0);
  for (int trial = 0; trial < 20; ++trial) {
    const EkfMatrix p = RandomCovariance(&rng);
    const Eigen::Matrix2d s = strain.h_jacobian * p * strain.h_jacobian.transpose() + strain.noise;
    Eigen::Matrix<double, kEkfStateSize, 2> k = p * strain.h_jacobian.transpose() * s.inverse();
    for (int i = 0; i < kEkfStateSize; ++i) {
      for (int j = 0; j < 2; ++j) k(i, j) *= 1.0 + 0.3 * n(rng);  // 30 % off the optimum
    }
    const EkfMatrix joseph = JosephCovariance<2>(p, k, strain.h_jacobian, strain.noise);
    const EkfMatrix textbook = TextbookJoseph<2>(p, k, strain.h_jacobian, strain.noise);
    const EkfMatrix expanded = p - k * s * k.transpose();  // only right at the optimal gain
    for (int i = 0; i < kEkfStateSize; ++i) {
      for (int j = 0; j < kEkfStateSize; ++j) {
        // Round-off relative to the scale of the entry's row and column.
        const double scale = std::sqrt(p(i, i) * p(j, j));
        EXPECT_NEAR(joseph(i, j), textbook(i, j), 1e-12 * scale) << i << ", " << j;
      }
    }
    EXPECT_GT((expanded - textbook).cwiseAbs().maxCoeff(), 1e-3 * textbook.cwiseAbs().maxCoeff());

    const Eigen::Matrix<double, kEkfStateSize, 2> k2 = Eigen::Matrix<double, kEkfStateSize, 2>::Random() * 0.01;
    const EkfMatrix joseph2 = JosephCovariance<2>(p, k2, motor.h_jacobian, motor.noise);
    const EkfMatrix textbook2 = TextbookJoseph<2>(p, k2, motor.h_jacobian, motor.noise);
    EXPECT_LE((joseph2 - textbook2).cwiseAbs().maxCoeff(), 1e-12 * textbook2.cwiseAbs().maxCoeff());
  }
}

// At the optimal gain all forms agree: P+ = P - K S K^T.
TEST(JosephCovarianceTest, EqualsTheStandardUpdateAtTheKalmanGain) {
  std::mt19937 rng(17);
  const GyroMeasurementModel gyro(0.005);
  const EkfMatrix p = RandomCovariance(&rng);
  const Eigen::Matrix<double, 1, 1> s = gyro.h_jacobian * p * gyro.h_jacobian.transpose() + gyro.noise;
  const Eigen::Matrix<double, kEkfStateSize, 1> k = p * gyro.h_jacobian.transpose() * s.inverse();
  const EkfMatrix joseph = JosephCovariance<1>(p, k, gyro.h_jacobian, gyro.noise);
  const EkfMatrix standard = p - k * s * k.transpose();
  for (int i = 0; i < kEkfStateSize; ++i) {
    for (int j = 0; j < kEkfStateSize; ++j) {
      EXPECT_NEAR(joseph(i, j), standard(i, j), 1e-10 * std::sqrt(p(i, i) * p(j, j))) << i << ", " << j;
    }
  }
}

// 1500 updates of a badly scaled covariance: symmetric to round-off (the
// factored product is not symmetric by construction) and positive definite.
TEST(JosephCovarianceTest, KeepsCovarianceSymmetricPositiveDefinite) {
  std::mt19937 rng(13);
  std::normal_distribution<double> n(0.0, 1.0);
  EkfMatrix cov = RandomCovariance(&rng);
  EkfState x = EkfState::Zero();
  const StrainMeasurementModel strain(2e-5);
  const MotorSpeedMeasurementModel motor(5.0);
  for (int k = 0; k < 1000; ++k) {
    const StrainMeasurementModel::Vector z(1e-5 * n(rng), 1e-5 * n(rng));
    KalmanUpdate(strain, ComputeInnovation(strain, cov, z, StrainMeasurementModel::Predict(x)), &x, &cov);
    if (k % 2 == 0) {
      const MotorSpeedMeasurementModel::Vector w(5.0 * n(rng), 5.0 * n(rng));
      KalmanUpdate(motor, ComputeInnovation(motor, cov, w, MotorSpeedMeasurementModel::Predict(x)), &x, &cov);
    }
  }
  const EkfState d = cov.diagonal().cwiseSqrt().cwiseInverse();
  const EkfMatrix scaled = d.asDiagonal() * cov * d.asDiagonal();  // correlations
  EXPECT_LE((scaled - scaled.transpose()).cwiseAbs().maxCoeff(), 1e-9);
  Eigen::LLT<EkfMatrix> llt(0.5 * (scaled + scaled.transpose()));
  EXPECT_EQ(llt.info(), Eigen::Success);
  // The gauge reading b1 + e1 cannot be less certain than R = (2e-5)^2 after an update.
  const Eigen::Matrix2d reading_cov = strain.h_jacobian * cov * strain.h_jacobian.transpose();
  EXPECT_LE(reading_cov(0, 0), 4e-10);
}

}  // namespace
}  // namespace birotor
