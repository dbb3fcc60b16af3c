// The EKF's process and measurement models: the gravity-cancellation fact that
// lets the filter drop x, z, phi; Jacobians against central differences; the
// fourth-order transition matrix against the RK4 step.
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
  return x;
}

TEST(EkfProcessModelTest, JacobianMatchesCentralDifferences) {
  const VehicleParams p;
  const EkfProcessModel model(p);
  std::mt19937 rng(3);
  // Steps per state, in its unit.
  const double kStep[kEkfStateSize] = {1e-7, 1e-7, 1e-5, 1e-5, 1e-5, 1e-3, 1e-3, 1e-6, 1e-6};
  for (int trial = 0; trial < 10; ++trial) {
    const EkfState x = HoverLikeState(&rng);
    EkfInput u;
    u.omega_cmd_rad_s[0] = 650.0;
    u.omega_cmd_rad_s[1] = 1300.0;  // above omega_max: clamped, still differentiable in x
    const EkfMatrix a = model.Jacobian(x, u);
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
  const double kStep[kEkfStateSize] = {1e-8, 1e-8, 1e-6, 1e-6, 1e-6, 1e-3, 1e-3, 1e-6, 1e-6};
  const EkfState x = HoverLikeState(&rng);
  EkfInput u;
  // Rotors at their command: the rotor speed (and so df/dmu) is constant over the step.
  u.omega_cmd_rad_s[0] = x(kOmega1);
  u.omega_cmd_rad_s[1] = x(kOmega2);
  const double dt_s = 0.001;
  const EkfMatrix phi = EkfProcessModel::Transition(model.Jacobian(x, u), dt_s);
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

// A badly scaled but valid covariance, as in the filter (b ~ 1e-5, omega ~ 10).
EkfMatrix RandomCovariance(std::mt19937* rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double kScale[kEkfStateSize] = {1e-5, 1e-5, 0.1, 0.01, 0.01, 10.0, 10.0, 0.1, 0.1};
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
    KalmanUpdate(strain, ComputeInnovation(strain, x, cov, z), &x, &cov);
    if (k % 2 == 0) {
      const MotorSpeedMeasurementModel::Vector w(5.0 * n(rng), 5.0 * n(rng));
      KalmanUpdate(motor, ComputeInnovation(motor, x, cov, w), &x, &cov);
    }
  }
  const EkfState d = cov.diagonal().cwiseSqrt().cwiseInverse();
  const EkfMatrix scaled = d.asDiagonal() * cov * d.asDiagonal();  // correlations
  EXPECT_LE((scaled - scaled.transpose()).cwiseAbs().maxCoeff(), 1e-9);
  Eigen::LLT<EkfMatrix> llt(0.5 * (scaled + scaled.transpose()));
  EXPECT_EQ(llt.info(), Eigen::Success);
  EXPECT_LE(cov(kDeflection1, kDeflection1), 4e-10);  // cannot exceed R = (2e-5)^2 after an update
}

}  // namespace
}  // namespace birotor
