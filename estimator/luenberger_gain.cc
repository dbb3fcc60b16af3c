#include "estimator/luenberger_gain.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

namespace birotor {
namespace {

constexpr int kChannelSize = 3;  // b, b_dot, force combination
using ChannelMatrix = Eigen::Matrix<double, kChannelSize, kChannelSize>;
using StrainMatrix = Eigen::Matrix<double, kStrainObservableSize, kStrainObservableSize>;
using StrainVector = Eigen::Matrix<double, kStrainObservableSize, 1>;

// z = T x: [b_s, b_s_dot, f1 - f2, b_d, b_d_dot, f1 + f2].
StrainMatrix ChannelTransform() {
  StrainMatrix t = StrainMatrix::Zero();
  const int pairs[3][2] = {
      {kLinDeflection1, kLinDeflection2}, {kLinDeflectionRate1, kLinDeflectionRate2}, {kLinForce1, kLinForce2}};
  for (int r = 0; r < kChannelSize; ++r) {
    // Sum channel: b1 + b2 is driven by f1 - f2; difference channel: b1 - b2 by f1 + f2.
    t(r, pairs[r][0]) = 1.0;
    t(r, pairs[r][1]) = r == 2 ? -1.0 : 1.0;
    t(kChannelSize + r, pairs[r][0]) = 1.0;
    t(kChannelSize + r, pairs[r][1]) = r == 2 ? 1.0 : -1.0;
  }
  return t;
}

// Natural frequency of the arm pair of channel j in continuous time [rad/s].
double ChannelArmFrequency(const StrainMatrix& a_channels_continuous, int channel) {
  const Eigen::Matrix2d arm = a_channels_continuous.block<2, 2>(channel * kChannelSize, channel * kChannelSize);
  return std::abs(arm.eigenvalues()(0));
}

void CheckOptions(const LinearForceModel& model, const LuenbergerOptions& options) {
  const double nyquist_hz = 0.5 / model.period_s;
  if (!(options.force_bandwidth_hz > 0 && options.force_bandwidth_hz < nyquist_hz)) {
    throw std::invalid_argument("luenberger: force_bandwidth_hz must be in (0, strain rate / 2)");
  }
  if (!(options.arm_damping_ratio > 0 && options.arm_damping_ratio < 1)) {
    throw std::invalid_argument("luenberger: arm_damping_ratio must be in (0, 1)");
  }
}

}  // namespace

std::array<std::complex<double>, kLinearStateSize> DesiredObserverPoles(const LinearForceModel& model,
                                                                        const LuenbergerOptions& options) {
  const StrainMatrix t = ChannelTransform();
  const StrainMatrix a_channels =
      t * model.a_continuous.topLeftCorner<kStrainObservableSize, kStrainObservableSize>() * t.inverse();
  const double zeta = options.arm_damping_ratio;
  std::array<std::complex<double>, kLinearStateSize> poles;
  for (int channel = 0; channel < 2; ++channel) {
    const double w_n = ChannelArmFrequency(a_channels, channel);
    const std::complex<double> s(-zeta * w_n, w_n * std::sqrt(1.0 - zeta * zeta));
    poles[channel * kChannelSize + 0] = std::exp(s * model.period_s);
    poles[channel * kChannelSize + 1] = std::exp(std::conj(s) * model.period_s);
    poles[channel * kChannelSize + 2] = std::exp(-2.0 * M_PI * options.force_bandwidth_hz * model.period_s);
  }
  poles[kLinPitchRate] = poles[2];
  return poles;
}

ObserverGains PlaceObserverPoles(const LinearForceModel& model, const LuenbergerOptions& options) {
  CheckOptions(model, options);
  const StrainMatrix t = ChannelTransform();
  const StrainMatrix t_inv = t.inverse();
  // Scaled channel coordinates z = D z_s, D = (deflection, rate, force) scale per channel.
  StrainVector channel_scale;
  for (int r = 0; r < kChannelSize; ++r) {
    channel_scale(r) = channel_scale(kChannelSize + r) = model.scale(kLinDeflection1 + 2 * r);
  }
  const StrainMatrix a_strain = model.a_discrete.topLeftCorner<kStrainObservableSize, kStrainObservableSize>();
  const StrainMatrix a_channels_scaled =
      channel_scale.cwiseInverse().asDiagonal() * (t * a_strain * t_inv) * channel_scale.asDiagonal();
  // The channels must not drive each other (mirror symmetry of the vehicle).
  const double coupling =
      std::max(a_channels_scaled.topRightCorner<kChannelSize, kChannelSize>().cwiseAbs().maxCoeff(),
               a_channels_scaled.bottomLeftCorner<kChannelSize, kChannelSize>().cwiseAbs().maxCoeff());
  if (coupling > 1e-9 * a_channels_scaled.cwiseAbs().maxCoeff()) {
    throw std::invalid_argument("luenberger: the sum and difference channels are coupled (asymmetric vehicle)");
  }
  const std::array<std::complex<double>, kLinearStateSize> poles = DesiredObserverPoles(model, options);

  // y_z = (b_s, b_d) = T_y y.
  Eigen::Matrix2d t_y;
  t_y << 1.0, 1.0, 1.0, -1.0;
  Eigen::Matrix<double, kStrainObservableSize, kLinearOutputSize> gain_channels =
      Eigen::Matrix<double, kStrainObservableSize, kLinearOutputSize>::Zero();
  for (int channel = 0; channel < 2; ++channel) {
    const int offset = channel * kChannelSize;
    // Scaled channel: states in (deflection, rate, force) scale, output in deflection scale.
    const ChannelMatrix a = a_channels_scaled.block<kChannelSize, kChannelSize>(offset, offset);
    const Eigen::RowVector3d c(1.0, 0.0, 0.0);
    const Eigen::RowVector3d h = c * a;  // filter form: the pair (A_j, C_j A_j)
    ChannelMatrix observability;
    observability << h, h * a, h * a * a;
    const std::complex<double> z_arm = poles[offset];
    const double z_force = poles[offset + 2].real();
    const ChannelMatrix identity = ChannelMatrix::Identity();
    const ChannelMatrix phi = (a * a - 2.0 * z_arm.real() * a + std::norm(z_arm) * identity) * (a - z_force * identity);
    const Eigen::Vector3d gain_scaled = phi * observability.inverse() * Eigen::Vector3d::UnitZ();
    // Back to physical units: x = D x_s, y_z = deflection_scale y_zs.
    for (int r = 0; r < kChannelSize; ++r) {
      gain_channels(offset + r, channel) = channel_scale(r) * gain_scaled(r) / channel_scale(0);
    }
  }
  ObserverGains gains;
  gains.strain.setZero();
  gains.strain.topRows<kStrainObservableSize>() = t_inv * gain_channels * t_y;
  // phi_dot: e+ = (1 - l) (phi_dot error after the prediction): pole 1 - l.
  gains.gyro.setZero();
  gains.gyro(kLinPitchRate) = 1.0 - poles[kLinPitchRate].real();
  return gains;
}

LinearMatrix ObserverErrorMatrix(const LinearForceModel& model, const ObserverGains& gains) {
  const LinearMatrix identity = LinearMatrix::Identity();
  return (identity - gains.strain * model.c) * (identity - gains.gyro * model.c_gyro) * model.a_discrete;
}

}  // namespace birotor
