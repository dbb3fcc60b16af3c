#include "estimator/linear_force_model.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "model/equilibrium.h"
#include "model/linearization.h"
#include "model/observability.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {

// Axes of the 12-state augmented model (AugmentedStateNames()) kept as the
// observable part, in LinearIndex order, and the axes that must be hidden.
constexpr int kObservableAxes[kLinearStateSize] = {kB1,        kB2,        kNumCoordinates + kB1, kNumCoordinates + kB2,
                                                   kAugForce1, kAugForce2, kNumCoordinates + kPhi};
const std::vector<std::string> kHiddenFromStrain = {"x", "z", "phi", "x_dot", "z_dot", "phi_dot"};
const std::vector<std::string> kHiddenFromStrainAndGyro = {"x", "z", "phi", "x_dot", "z_dot"};

void CheckHidden(const AugMatrix& a, const std::vector<std::string>& measured,
                 const std::vector<std::string>& expected_hidden) {
  Eigen::MatrixXd c;
  std::string unknown;
  SelectionMatrix(AugmentedStateNames(), measured, &c, &unknown);
  const SubspaceReport report = AnalyzeObservability(a, c, AugmentedStateNames());
  if (report.rank != kAugStateSize - static_cast<int>(expected_hidden.size()) ||
      report.hidden_states != expected_hidden) {
    throw std::invalid_argument("linear model: unexpected observable part (rank " + std::to_string(report.rank) + ")");
  }
}

}  // namespace

LinearForceModel BuildLinearForceModel(const BirotorParams& params, const EkfOptions& noise,
                                       const LinearModelOptions& options) {
  if (!(options.strain_rate_hz >= 1.0 && options.strain_rate_hz <= 1e6)) {
    throw std::invalid_argument("linear model: strain_rate_hz out of [1, 1e6]");
  }
  const AugMatrix a_aug = AugmentWithForces(LinearizeAtHover(params));
  CheckHidden(a_aug, {"b1", "b2"}, kHiddenFromStrain);
  CheckHidden(a_aug, {"b1", "b2", "phi_dot"}, kHiddenFromStrainAndGyro);
  // Orthogonal Kalman decomposition with the axis basis: W selects the
  // observable axes, N the hidden ones. A_o = W^T A W is the observable
  // block when W^T A N = 0 (the hidden subspace is A-invariant).
  Eigen::Matrix<double, kAugStateSize, kLinearStateSize> w =
      Eigen::Matrix<double, kAugStateSize, kLinearStateSize>::Zero();
  for (int j = 0; j < kLinearStateSize; ++j) w(kObservableAxes[j], j) = 1.0;
  const Eigen::Matrix<double, kAugStateSize, kLinearStateSize> a_w = a_aug * w;
  // W^T A N: observable rows, hidden columns.
  const Eigen::Matrix<double, kLinearStateSize, kAugStateSize> w_t_a = w.transpose() * a_aug;
  const double hidden_to_observable = (w_t_a - (w_t_a * w) * w.transpose()).cwiseAbs().maxCoeff();
  if (hidden_to_observable > 1e-9 * a_aug.cwiseAbs().maxCoeff()) {
    throw std::invalid_argument("linear model: the hidden states drive the observable ones");
  }

  LinearForceModel model;
  model.a_continuous = w.transpose() * a_w;
  model.c.setZero();
  model.c(0, kLinDeflection1) = 1.0;
  model.c(1, kLinDeflection2) = 1.0;
  model.c_gyro.setZero();
  model.c_gyro(0, kLinPitchRate) = 1.0;
  if (model.a_continuous.topRightCorner<kStrainObservableSize, 1>().cwiseAbs().maxCoeff() != 0.0) {
    throw std::invalid_argument("linear model: phi_dot drives the arms at hover");
  }
  model.period_s = 1.0 / options.strain_rate_hz;

  const Equilibrium eq = SolveHoverEquilibrium(params);
  for (int i = 0; i < kBirotorRotors; ++i) {
    model.deflection_hover_rad[i] = eq.deflection_rad[i];
    model.force_hover_n[i] = eq.force_n[i];
  }
  model.force_psd_n2_s = options.force_psd_n2_s;
  model.noise_continuous.setZero();
  model.noise_continuous(kLinDeflectionRate1, kLinDeflectionRate1) = noise.deflection_rate_psd_rad2_s3;
  model.noise_continuous(kLinDeflectionRate2, kLinDeflectionRate2) = noise.deflection_rate_psd_rad2_s3;
  model.noise_continuous(kLinForce1, kLinForce1) = model.force_psd_n2_s;
  model.noise_continuous(kLinForce2, kLinForce2) = model.force_psd_n2_s;
  model.noise_continuous(kLinPitchRate, kLinPitchRate) = noise.pitch_rate_psd_rad2_s3;

  // Scaling: forces in newtons; deflections in the static deflection of one
  // newton, |A_bb^-1 A_bf| (about 1e-4 rad); rates in that deflection times
  // the fastest arm frequency. The blocks of A T, C and Q are then O(1)
  // instead of spanning 1 to 2e5 (the trap of the thesis's rank test).
  const Eigen::Matrix2d a_bb = model.a_continuous.block<2, 2>(kLinDeflectionRate1, kLinDeflection1);
  const Eigen::Matrix2d a_bf = model.a_continuous.block<2, 2>(kLinDeflectionRate1, kLinForce1);
  const double deflection_per_newton = (a_bb.inverse() * a_bf).cwiseAbs().maxCoeff();
  const double arm_rad_s = std::sqrt(a_bb.eigenvalues().cwiseAbs().maxCoeff());
  const double rate_scale = deflection_per_newton * arm_rad_s;
  model.scale << deflection_per_newton, deflection_per_newton, rate_scale, rate_scale, 1.0, 1.0, rate_scale;

  // Exact discretisation in scaled coordinates (Van Loan):
  //   expm([[-A, Q_c], [0, A^T]] T) = [[., F12], [0, F22]],  A_d = F22^T,  Q_d = A_d F12.
  const LinearMatrix s = model.scale.asDiagonal();
  const LinearMatrix s_inv = model.scale.cwiseInverse().asDiagonal();
  const LinearMatrix a_s = s_inv * model.a_continuous * s;
  const LinearMatrix q_s = s_inv * model.noise_continuous * s_inv;
  Eigen::Matrix<double, 2 * kLinearStateSize, 2 * kLinearStateSize> van_loan;
  van_loan << -a_s, q_s, LinearMatrix::Zero(), a_s.transpose();
  const Eigen::Matrix<double, 2 * kLinearStateSize, 2 * kLinearStateSize> f = (van_loan * model.period_s).exp();
  const LinearMatrix a_d_s = f.bottomRightCorner<kLinearStateSize, kLinearStateSize>().transpose();
  LinearMatrix q_d_s = a_d_s * f.topRightCorner<kLinearStateSize, kLinearStateSize>();
  q_d_s = 0.5 * (q_d_s + q_d_s.transpose()).eval();
  model.a_discrete = s * a_d_s * s_inv;
  model.noise_discrete = s * q_d_s * s;
  return model;
}

}  // namespace birotor
