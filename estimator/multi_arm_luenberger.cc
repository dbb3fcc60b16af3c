#include "estimator/multi_arm_luenberger.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

namespace birotor {
namespace {

using Layout = MultiArmLinearLayout;
constexpr int kChannelSize = 3;  // m_j, m_j_dot, g_j

// Each row scaled to a largest |entry| of 1 (the gain does not depend on it).
Eigen::MatrixXd UnitRows(Eigen::MatrixXd t) {
  for (int r = 0; r < t.rows(); ++r) t.row(r) /= t.row(r).cwiseAbs().maxCoeff();
  return t;
}

// z = T x over the 3N strain-observable states, channel by channel.
Eigen::MatrixXd ChannelTransform(const MultiArmObserverChannels& channels) {
  const int n = static_cast<int>(channels.deflection_transform.rows());
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(kChannelSize * n, kChannelSize * n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      t(kChannelSize * j + 0, Layout::Deflection(i)) = channels.deflection_transform(j, i);
      t(kChannelSize * j + 1, Layout::DeflectionRate(n, i)) = channels.deflection_transform(j, i);
      t(kChannelSize * j + 2, Layout::Force(n, i)) = channels.force_transform(j, i);
    }
  }
  return t;
}

void CheckOptions(const MultiArmLinearForceModel& model, const LuenbergerOptions& options) {
  const double nyquist_hz = 0.5 / model.period_s;
  if (!(options.force_bandwidth_hz > 0 && options.force_bandwidth_hz < nyquist_hz)) {
    throw std::invalid_argument("luenberger: force_bandwidth_hz must be in (0, strain rate / 2)");
  }
  if (!(options.arm_damping_ratio > 0 && options.arm_damping_ratio < 1)) {
    throw std::invalid_argument("luenberger: arm_damping_ratio must be in (0, 1)");
  }
}

// Eigenstructure assignment on the scaled strain block, filter form: the
// error matrix E = A - L H with H = C A has left eigenvectors u_k for the
// poles z_k, u_k^T (A - z_k I) = (u_k^T L) H = w_k^T H, so for a chosen
// output direction w_k,
//   u_k = (A^T - z_k I)^-1 H^T w_k,   and   U^T L = W^T  gives  L = U^-T W^T.
// Channel j's three poles take w = row j of T_b (its output m_j): on a
// vehicle whose channels decouple this is the channel's Ackermann gain (the
// gain of a single-output channel with given poles is unique); where they
// are coupled the same poles are still placed exactly.
Eigen::MatrixXd AssignEigenstructure(const Eigen::MatrixXd& a, const Eigen::MatrixXd& h,
                                     const std::vector<std::complex<double>>& poles,
                                     const Eigen::MatrixXd& output_directions) {
  const int s = static_cast<int>(a.rows());
  const int n = static_cast<int>(h.rows());
  Eigen::MatrixXcd u(s, s), w(n, s);
  const Eigen::MatrixXcd a_t = a.transpose().cast<std::complex<double>>();
  const Eigen::MatrixXcd identity = Eigen::MatrixXcd::Identity(s, s);
  for (int k = 0; k < s; ++k) {
    const Eigen::VectorXcd direction = output_directions.row(k / kChannelSize).transpose().cast<std::complex<double>>();
    w.col(k) = direction;
    u.col(k) = (a_t - poles[static_cast<size_t>(k)] * identity).partialPivLu().solve(h.transpose() * direction);
  }
  const Eigen::MatrixXcd gain = u.transpose().partialPivLu().solve(w.transpose());
  return gain.real();
}

}  // namespace

MultiArmObserverChannels MultiArmArmChannels(const MultiArmLinearForceModel& model) {
  const int n = model.arm_count;
  const Eigen::MatrixXd a_bb = model.a_continuous.block(Layout::DeflectionRate(n, 0), Layout::Deflection(0), n, n);
  const Eigen::MatrixXd a_bf = model.a_continuous.block(Layout::DeflectionRate(n, 0), Layout::Force(n, 0), n, n);
  const Eigen::EigenSolver<Eigen::MatrixXd> modes(a_bb);
  if (modes.eigenvalues().imag().cwiseAbs().maxCoeff() > 1e-9 * modes.eigenvalues().cwiseAbs().maxCoeff()) {
    throw std::invalid_argument("luenberger: the arm stiffness block has complex modes");
  }
  MultiArmObserverChannels channels;
  channels.deflection_transform = UnitRows(modes.eigenvectors().real().inverse());
  channels.force_transform = UnitRows(channels.deflection_transform * a_bf);
  channels.arm_frequency_rad_s = Eigen::VectorXd::Zero(n);
  const Eigen::MatrixXd t = ChannelTransform(channels);
  const int s = Layout::StrainObservableSize(n);
  const Eigen::MatrixXd a_channels = t * model.a_continuous.topLeftCorner(s, s) * t.inverse();
  for (int j = 0; j < n; ++j) {
    const Eigen::Matrix2d arm = a_channels.block<2, 2>(kChannelSize * j, kChannelSize * j);
    channels.arm_frequency_rad_s(j) = std::abs(arm.eigenvalues()(0));
  }
  return channels;
}

std::vector<std::complex<double>> DesiredMultiArmObserverPoles(const MultiArmLinearForceModel& model,
                                                               const LuenbergerOptions& options) {
  const MultiArmObserverChannels channels = MultiArmArmChannels(model);
  const int n = model.arm_count;
  const double zeta = options.arm_damping_ratio;
  const std::complex<double> force_pole(std::exp(-2.0 * M_PI * options.force_bandwidth_hz * model.period_s), 0.0);
  std::vector<std::complex<double>> poles;
  for (int j = 0; j < n; ++j) {
    const double w_n = channels.arm_frequency_rad_s(j);
    const std::complex<double> s(-zeta * w_n, w_n * std::sqrt(1.0 - zeta * zeta));
    poles.push_back(std::exp(s * model.period_s));
    poles.push_back(std::exp(std::conj(s) * model.period_s));
    poles.push_back(force_pole);
  }
  poles.push_back(force_pole);  // phi_dot
  return poles;
}

MultiArmObserverGains PlaceMultiArmObserverPoles(const MultiArmLinearForceModel& model,
                                                 const LuenbergerOptions& options) {
  CheckOptions(model, options);
  const int n = model.arm_count;
  const int s = Layout::StrainObservableSize(n);
  const MultiArmObserverChannels channels = MultiArmArmChannels(model);
  // Scaled coordinates x = D x_s, y = scale_b y_s (every block O(1)).
  const Eigen::VectorXd d = model.scale.head(s);
  const double output_scale = model.scale(Layout::Deflection(0));
  const Eigen::MatrixXd a_scaled =
      d.cwiseInverse().asDiagonal() * model.a_discrete.topLeftCorner(s, s) * d.asDiagonal();
  Eigen::MatrixXd c_scaled = Eigen::MatrixXd::Zero(n, s);
  for (int i = 0; i < n; ++i) c_scaled(i, Layout::Deflection(i)) = d(Layout::Deflection(i)) / output_scale;
  const std::vector<std::complex<double>> poles = DesiredMultiArmObserverPoles(model, options);
  const Eigen::MatrixXd gain_scaled =
      AssignEigenstructure(a_scaled, c_scaled * a_scaled, poles, channels.deflection_transform);
  MultiArmObserverGains gains;
  gains.strain = Eigen::MatrixXd::Zero(Layout::StateSize(n), n);
  gains.strain.topRows(s) = d.asDiagonal() * gain_scaled / output_scale;
  // phi_dot: e+ = (1 - l) (its error after the prediction): pole 1 - l.
  gains.gyro = Eigen::VectorXd::Zero(Layout::StateSize(n));
  gains.gyro(Layout::PitchRate(n)) = 1.0 - poles.back().real();
  return gains;
}

Eigen::MatrixXd MultiArmObserverErrorMatrix(const MultiArmLinearForceModel& model, const MultiArmObserverGains& gains) {
  const int n = model.arm_count;
  const int size = Layout::StateSize(n);
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(n, size);
  for (int i = 0; i < n; ++i) c(i, Layout::Deflection(i)) = 1.0;
  Eigen::MatrixXd c_gyro = Eigen::MatrixXd::Zero(1, size);
  c_gyro(0, Layout::PitchRate(n)) = 1.0;
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(size, size);
  return (identity - gains.strain * c) * (identity - gains.gyro * c_gyro) * model.a_discrete;
}

}  // namespace birotor
