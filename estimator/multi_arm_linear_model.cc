#include "estimator/multi_arm_linear_model.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "model/multi_arm_linearization.h"
#include "model/observability.h"

namespace birotor {
namespace {

using Layout = MultiArmLinearLayout;

// Axes of the augmented model [q; v; f] (q = x, z, phi, b_1 .. b_N) kept as
// the observable part, in MultiArmLinearLayout order.
std::vector<int> ObservableAxes(int n_arms) {
  const int n_q = 3 + n_arms;
  std::vector<int> axes(static_cast<size_t>(Layout::StateSize(n_arms)));
  for (int i = 0; i < n_arms; ++i) {
    axes[static_cast<size_t>(Layout::Deflection(i))] = 3 + i;
    axes[static_cast<size_t>(Layout::DeflectionRate(n_arms, i))] = n_q + 3 + i;
    axes[static_cast<size_t>(Layout::Force(n_arms, i))] = 2 * n_q + i;
  }
  axes[static_cast<size_t>(Layout::PitchRate(n_arms))] = n_q + 2;  // phi_dot
  return axes;
}

// The staircase test of the birotor's model (linear_force_model.cc): the
// states hidden from the measured ones must be exactly expected_hidden.
void CheckHidden(const Eigen::MatrixXd& a, int n_arms, const std::vector<std::string>& measured,
                 const std::vector<std::string>& expected_hidden) {
  const std::vector<std::string> names = MultiArmStateNames(n_arms);
  Eigen::MatrixXd c;
  std::string unknown;
  SelectionMatrix(names, measured, &c, &unknown);
  const SubspaceReport report = AnalyzeObservability(a, c, names);
  if (report.rank != static_cast<int>(names.size() - expected_hidden.size()) ||
      report.hidden_states != expected_hidden) {
    throw std::invalid_argument("N-arm linear model: unexpected observable part (rank " + std::to_string(report.rank) +
                                " of " + std::to_string(names.size()) + ")");
  }
}

std::vector<std::string> GaugeNames(int n_arms) {
  std::vector<std::string> names;
  for (int i = 1; i <= n_arms; ++i) names.push_back("b" + std::to_string(i));
  return names;
}

void FillNoise(const EkfOptions& noise, MultiArmLinearForceModel* model) {
  const int n = model->arm_count;
  model->noise_continuous = Eigen::MatrixXd::Zero(Layout::StateSize(n), Layout::StateSize(n));
  for (int i = 0; i < n; ++i) {
    model->noise_continuous(Layout::DeflectionRate(n, i), Layout::DeflectionRate(n, i)) =
        noise.deflection_rate_psd_rad2_s3;
    model->noise_continuous(Layout::Force(n, i), Layout::Force(n, i)) = model->force_psd_n2_s;
  }
  model->noise_continuous(Layout::PitchRate(n), Layout::PitchRate(n)) = noise.pitch_rate_psd_rad2_s3;
}

// Forces in newtons; deflections in the static deflection of one newton,
// max |A_bb^-1 A_bf|; rates in that deflection times the fastest arm
// frequency sqrt(max |eig A_bb|) (linear_force_model.cc).
void FillScale(MultiArmLinearForceModel* model) {
  const int n = model->arm_count;
  const Eigen::MatrixXd a_bb = model->a_continuous.block(Layout::DeflectionRate(n, 0), Layout::Deflection(0), n, n);
  const Eigen::MatrixXd a_bf = model->a_continuous.block(Layout::DeflectionRate(n, 0), Layout::Force(n, 0), n, n);
  const double deflection_per_newton = (a_bb.inverse() * a_bf).cwiseAbs().maxCoeff();
  const double arm_rad_s = std::sqrt(a_bb.eigenvalues().cwiseAbs().maxCoeff());
  const double rate_scale = deflection_per_newton * arm_rad_s;
  model->scale = Eigen::VectorXd::Ones(Layout::StateSize(n));
  for (int i = 0; i < n; ++i) {
    model->scale(Layout::Deflection(i)) = deflection_per_newton;
    model->scale(Layout::DeflectionRate(n, i)) = rate_scale;
  }
  model->scale(Layout::PitchRate(n)) = rate_scale;
}

// Exact discretisation in scaled coordinates (Van Loan):
//   expm([[-A, Q_c], [0, A^T]] T) = [[., F12], [0, F22]],  A_d = F22^T,  Q_d = A_d F12.
void Discretize(MultiArmLinearForceModel* model) {
  const int s_n = static_cast<int>(model->scale.size());
  const Eigen::MatrixXd s = model->scale.asDiagonal();
  const Eigen::MatrixXd s_inv = model->scale.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd a_s = s_inv * model->a_continuous * s;
  const Eigen::MatrixXd q_s = s_inv * model->noise_continuous * s_inv;
  Eigen::MatrixXd van_loan(2 * s_n, 2 * s_n);
  van_loan << -a_s, q_s, Eigen::MatrixXd::Zero(s_n, s_n), a_s.transpose();
  const Eigen::MatrixXd f = (van_loan * model->period_s).exp();
  const Eigen::MatrixXd a_d_s = f.bottomRightCorner(s_n, s_n).transpose();
  Eigen::MatrixXd q_d_s = a_d_s * f.topRightCorner(s_n, s_n);
  q_d_s = 0.5 * (q_d_s + q_d_s.transpose()).eval();
  model->a_discrete = s * a_d_s * s_inv;
  model->noise_discrete = s * q_d_s * s;
}

}  // namespace

MultiArmLinearForceModel BuildMultiArmLinearForceModel(const VehicleDescription& vehicle, const EkfOptions& noise,
                                                       const LinearModelOptions& options) {
  if (!(options.strain_rate_hz >= 1.0 && options.strain_rate_hz <= 1e6)) {
    throw std::invalid_argument("N-arm linear model: strain_rate_hz out of [1, 1e6]");
  }
  const int n = vehicle.arm_count;
  const MultiArmHover hover = SolveMultiArmHover(vehicle);
  if (!hover.converged) throw std::invalid_argument("N-arm linear model: no hover equilibrium");
  const Eigen::MatrixXd a_aug = AugmentMultiArmWithForces(LinearizeMultiArmAtHover(vehicle, hover));
  std::vector<std::string> measured = GaugeNames(n);
  CheckHidden(a_aug, n, measured, {"x", "z", "phi", "x_dot", "z_dot", "phi_dot"});
  measured.push_back("phi_dot");
  CheckHidden(a_aug, n, measured, {"x", "z", "phi", "x_dot", "z_dot"});

  // Orthogonal Kalman decomposition with the axis basis: W selects the kept
  // axes; A_o = W^T A W is the observable block when W^T A N = 0.
  const std::vector<int> axes = ObservableAxes(n);
  const int size = Layout::StateSize(n);
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(a_aug.rows(), size);
  for (int j = 0; j < size; ++j) w(axes[static_cast<size_t>(j)], j) = 1.0;
  const Eigen::MatrixXd w_t_a = w.transpose() * a_aug;
  const double hidden_to_observable = (w_t_a - (w_t_a * w) * w.transpose()).cwiseAbs().maxCoeff();
  if (hidden_to_observable > 1e-9 * a_aug.cwiseAbs().maxCoeff()) {
    throw std::invalid_argument("N-arm linear model: the hidden states drive the observable ones");
  }
  MultiArmLinearForceModel model;
  model.arm_count = n;
  model.a_continuous = w_t_a * w;
  if (model.a_continuous.col(Layout::PitchRate(n)).head(Layout::StrainObservableSize(n)).cwiseAbs().maxCoeff() != 0.0) {
    throw std::invalid_argument("N-arm linear model: phi_dot drives the arms at hover");
  }
  model.period_s = 1.0 / options.strain_rate_hz;
  model.deflection_hover_rad = hover.deflection_rad;
  model.force_hover_n = hover.force_n;
  model.force_psd_n2_s = options.force_psd_n2_s;
  FillNoise(noise, &model);
  FillScale(&model);
  Discretize(&model);
  return model;
}

}  // namespace birotor
