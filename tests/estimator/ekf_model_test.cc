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

TEST(JosephUpdateTest, KeepsCovarianceSymmetricPositiveDefinite) {
  std::mt19937 rng(13);
  std::normal_distribution<double> n(0.0, 1.0);
  // A badly scaled but valid covariance, as in the filter (b ~ 1e-5, omega ~ 10).
  const double kScale[kEkfStateSize] = {1e-5, 1e-5, 0.1, 0.01, 0.01, 10.0, 10.0, 0.1, 0.1};
  EkfMatrix root;
  for (int i = 0; i < kEkfStateSize; ++i) {
    for (int j = 0; j < kEkfStateSize; ++j) root(i, j) = n(rng) * kScale[i];
  }
  EkfMatrix cov = root * root.transpose();
  EkfState x = EkfState::Zero();
  const StrainMeasurementModel strain(2e-5);
  const MotorSpeedMeasurementModel motor(5.0);
  for (int k = 0; k < 1000; ++k) {
    const StrainMeasurementModel::Vector z(1e-5 * n(rng), 1e-5 * n(rng));
    JosephUpdate(strain, ComputeInnovation(strain, x, cov, z), &x, &cov);
    if (k % 2 == 0) {
      const MotorSpeedMeasurementModel::Vector w(5.0 * n(rng), 5.0 * n(rng));
      JosephUpdate(motor, ComputeInnovation(motor, x, cov, w), &x, &cov);
    }
  }
  EXPECT_LE((cov - cov.transpose()).cwiseAbs().maxCoeff(), 1e-12 * cov.cwiseAbs().maxCoeff());
  // Positive definite: Cholesky of the diagonally scaled matrix succeeds.
  const EkfState d = cov.diagonal().cwiseSqrt().cwiseInverse();
  const EkfMatrix scaled = d.asDiagonal() * cov * d.asDiagonal();
  Eigen::LLT<EkfMatrix> llt(0.5 * (scaled + scaled.transpose()));
  EXPECT_EQ(llt.info(), Eigen::Success);
  EXPECT_LE(cov(kDeflection1, kDeflection1), 4e-10);  // cannot exceed R after an update
}

}  // namespace
}  // namespace birotor
