#include "estimator/multi_arm_linear_estimator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "estimator/linear_method_reports.h"
#include "estimator/multi_arm_luenberger.h"

namespace birotor {
namespace {

constexpr double kMicrosecond = 1e-6;
// b_i of an arm without a reading at initialisation: the hover deflection
// with this sigma [rad] (the N-arm EKF's kUnmeasuredDeflectionStdRad).
constexpr double kUnmeasuredDeflectionStdRad = 0.01;
// Below this share of the hover thrusts the body rests on the ground [1].
constexpr double kSupportedForceShare = 0.5;

}  // namespace

template <int N>
MultiArmLinearEstimator<N>::MultiArmLinearEstimator(const VehicleDescription& vehicle, const EkfOptions& noise,
                                                    const LinearModelOptions& options)
    : kalman_(true),
      vehicle_(vehicle),
      noise_(noise),
      model_(BuildMultiArmLinearForceModel(vehicle, noise, options)),
      motor_(vehicle),
      strain_gate_(noise.gate_consecutive_limit),
      gyro_gate_(noise.gate_consecutive_limit),
      faults_(noise) {
  scale_ = model_.scale;
  const Matrix s_inv = scale_.cwiseInverse().asDiagonal();
  a_ = s_inv * Matrix(model_.a_discrete) * scale_.asDiagonal();
  q_ = s_inv * Matrix(model_.noise_discrete) * s_inv;
  const double strain_std = noise.strain_noise_rad / scale_(Layout::Deflection(0));
  strain_variance_s_ = strain_std * strain_std;
  const double gyro_std = noise.gyro_noise_rad_s / scale_(Layout::PitchRate(N));
  gyro_noise_(0, 0) = gyro_std * gyro_std;
  const double pitch_rate_std = noise.initial_pitch_rate_std_rad_s / scale_(Layout::PitchRate(N));
  pitch_rate_variance_s_ = pitch_rate_std * pitch_rate_std;
  fixed_gain_s_.setZero();
  fixed_gyro_gain_s_.setZero();
  Reset();
}

template <int N>
MultiArmLinearEstimator<N>::MultiArmLinearEstimator(const VehicleDescription& vehicle, const EkfOptions& noise,
                                                    const LinearModelOptions& options,
                                                    const LuenbergerOptions& observer)
    : MultiArmLinearEstimator(vehicle, noise, options) {
  kalman_ = false;
  const MultiArmObserverGains gains = PlaceMultiArmObserverPoles(model_, observer);
  // Scaled: x_s += diag(1/scale) L scale_y y_s.
  fixed_gain_s_ = scale_.cwiseInverse().asDiagonal() * StrainGain(gains.strain) * scale_(Layout::Deflection(0));
  fixed_gyro_gain_s_ = scale_.cwiseInverse().asDiagonal() * GyroGain(gains.gyro) * scale_(Layout::PitchRate(N));
}

template <int N>
void MultiArmLinearEstimator<N>::DropPendingGyro() {
  if (gyro_pending_) reports_.Add(MakeFusionReport(FusionSource::kGyro, gyro_.utime, FusionOutcome::kNotFused));
  gyro_pending_ = false;
}

template <int N>
double MultiArmLinearEstimator<N>::Gate(FusionSource source) const {
  return LinearMethodGate(noise_, source);
}

template <int N>
void MultiArmLinearEstimator<N>::Reset() {
  reports_.Open();
  DropPendingGyro();
  motor_.Reset();
  initialized_ = false;
  converged_ = false;
  strain_gate_.Reset();
  gyro_gate_.Reset();
  faults_.Reset();
  supported_ = false;
  state_.setZero();
  covariance_.setIdentity();
  force_std_n_.fill(std::numeric_limits<double>::infinity());
  facts_ = MultiArmFilterFacts();
}

template <int N>
void MultiArmLinearEstimator<N>::AddMotor(const MultiArmMotorSample& sample) {
  reports_.Open();
  if (motor_.AddMotor(sample)) {
    reports_.Add(MakeFusionReport(FusionSource::kTelemetry, sample.utime, FusionOutcome::kFused));
  }
}

template <int N>
void MultiArmLinearEstimator<N>::AddImu(const ImuSample& sample) {
  reports_.Open();
  if (!noise_.use_gyro || !std::isfinite(sample.gyro_y_rad_s)) {
    reports_.Add(MakeFusionReport(FusionSource::kGyro, sample.utime, FusionOutcome::kNotFused));
    return;
  }
  DropPendingGyro();  // an older one not yet fused is replaced
  gyro_ = sample;
  gyro_pending_ = true;
}

template <int N>
void MultiArmLinearEstimator<N>::ScaledStrain(const MultiArmStrainSample& sample, Eigen::Matrix<double, N, 1>* z,
                                              std::array<bool, N>* measured) const {
  for (int i = 0; i < N; ++i) {
    const size_t k = static_cast<size_t>(i);
    const ArmDescription& arm = vehicle_.arms[k];
    // The description's calibration: the gauge reads s_i b_i + o_i.
    const double calibrated = (sample.deflection_rad[k] - arm.gauge_offset_rad) / arm.gauge_scale;
    (*measured)[k] = sample.n_arms == N && arm.has_gauge && std::isfinite(calibrated);
    (*z)(i) = (*measured)[k] ? (calibrated - model_.deflection_hover_rad(i)) / scale_(Layout::Deflection(i)) : 0.0;
  }
}

template <int N>
void MultiArmLinearEstimator<N>::Initialize(const MultiArmStrainSample& sample) {
  // Deflections from the sample, rates 0, forces at hover; the EKF's initial
  // uncertainties (thrust scale sigma at the hover force).
  Eigen::Matrix<double, N, 1> z;
  std::array<bool, N> measured;
  ScaledStrain(sample, &z, &measured);
  state_.setZero();
  covariance_.setZero();
  for (int i = 0; i < N; ++i) {
    const int b = Layout::Deflection(i), r = Layout::DeflectionRate(N, i), f = Layout::Force(N, i);
    const double unmeasured_std = kUnmeasuredDeflectionStdRad / scale_(b);
    state_(b) = z(i);
    covariance_(b, b) = measured[static_cast<size_t>(i)] ? strain_variance_s_ : unmeasured_std * unmeasured_std;
    const double rate_std = noise_.initial_deflection_rate_std_rad_s / scale_(r);
    covariance_(r, r) = rate_std * rate_std;
    const double force_std = noise_.initial_thrust_scale_std * model_.force_hover_n(i) / scale_(f);
    covariance_(f, f) = force_std * force_std;
  }
  covariance_(Layout::PitchRate(N), Layout::PitchRate(N)) = pitch_rate_variance_s_;
  DropPendingGyro();
  strain_gate_.Reset();
  gyro_gate_.Reset();
  faults_.Reset();
  converged_ = false;
  last_utime_ = sample.utime;
  initialized_ = true;
}

template <int N>
void MultiArmLinearEstimator<N>::Predict(int periods) {
  // x = A_d x, P = A_d P A_d^T + Q_d, once per strain period.
  Matrix temp;
  for (int k = 0; k < periods; ++k) {
    state_ = a_ * state_;
    temp.noalias() = a_.lazyProduct(covariance_);
    covariance_.noalias() = temp.lazyProduct(a_.transpose());
    covariance_ += q_;
  }
}

template <int N>
void MultiArmLinearEstimator<N>::UpdateGyro() {
  if (!gyro_pending_) return;
  if (supported_) {
    DropPendingGyro();  // the held body's pitch is not the hover model's
    return;
  }
  gyro_pending_ = false;
  // y = phi_dot_meas - phi_dot; the Kalman gain, or the observer's L_g.
  MeasurementLinearization<1, kSize> at;
  at.jacobian.setZero();
  at.jacobian(0, Layout::PitchRate(N)) = 1.0;
  at.predicted(0) = state_(Layout::PitchRate(N));
  const double pitch_rate_scale = scale_(Layout::PitchRate(N));
  const Eigen::Matrix<double, 1, 1> z(gyro_.gyro_y_rad_s / pitch_rate_scale);
  // After gate_consecutive_limit gyro samples gated in a row the pitch rate
  // is taken as lost (a lift-off's thrust ramp, which the hover model does
  // not follow, left it rad/s off): its variance grows by the initial one
  // and the gyro is fused ungated (else it stays gated for the flight).
  const auto inflate = [this](Matrix* cov) {
    (*cov)(Layout::PitchRate(N), Layout::PitchRate(N)) += pitch_rate_variance_s_;
  };
  const FusionReport report =
      gyro_gate_.Fuse(at, gyro_noise_, z, {FusionSource::kGyro, gyro_.utime, noise_.gyro_gate_nis}, &state_,
                      &covariance_, inflate, kalman_ ? nullptr : &fixed_gyro_gain_s_);
  reports_.Add(LinearReportInPhysicalUnits(report, pitch_rate_scale));
}

template <int N>
FusionReport MultiArmLinearEstimator<N>::UpdateStrain(const MultiArmStrainSample& sample) {
  // y = z - C x (C selects the read deflections); an arm without a reading
  // has a zero row, a unit variance and (observer) a zero gain column.
  Eigen::Matrix<double, N, 1> z;
  std::array<bool, N> measured;
  ScaledStrain(sample, &z, &measured);
  MeasurementLinearization<N, kSize> at;
  at.jacobian.setZero();
  Eigen::Matrix<double, N, N> noise = Eigen::Matrix<double, N, N>::Zero();
  StrainGain gain = fixed_gain_s_;
  for (int i = 0; i < N; ++i) {
    const bool read = measured[static_cast<size_t>(i)];
    at.jacobian(i, Layout::Deflection(i)) = read ? 1.0 : 0.0;
    at.predicted(i) = read ? state_(Layout::Deflection(i)) : 0.0;
    noise(i, i) = read ? strain_variance_s_ : 1.0;
    if (!read) gain.col(i).setZero();
  }
  // After gate_consecutive_limit rejections in a row: open up the forces
  // (the EKF's inflation of var(mu_i), at the hover force), then fuse.
  const auto inflate = [this](Matrix* cov) {
    for (int i = 0; i < N; ++i) {
      const int f = Layout::Force(N, i);
      const double extra = noise_.gate_inflation_thrust_scale_std * model_.force_hover_n(i) / scale_(f);
      (*cov)(f, f) += extra * extra;
    }
  };
  FusionReport report = strain_gate_.Fuse(at, noise, z, {FusionSource::kStrain, sample.utime, noise_.strain_gate_nis},
                                          &state_, &covariance_, inflate, kalman_ ? nullptr : &gain);
  report = LinearReportInPhysicalUnits(report, scale_(Layout::Deflection(0)));
  for (int i = 0; i < N; ++i) {
    if (!measured[static_cast<size_t>(i)]) report.innovation_variance(i) = 0.0;  // left out (FusionReport)
  }
  return report;
}

template <int N>
void MultiArmLinearEstimator<N>::UpdateFaults(int64_t utime) {
  // mu_i = f_i / (c_T,i omega_i^2), P_mu = D P_f D with D = diag(scale_f / nominal_i).
  if (!motor_.has_motor()) return;
  MultiArmFaultMonitor::ScaleVector mu = MultiArmFaultMonitor::ScaleVector::Zero();
  MultiArmFaultMonitor::ScaleMatrix p_mu = MultiArmFaultMonitor::ScaleMatrix::Zero();
  Eigen::Matrix<double, N, 1> d;
  for (int i = 0; i < N; ++i) {
    const double nominal = motor_.NominalForceN(i);
    if (!(nominal > 1e-6)) return;  // a stopped rotor: no efficiency to judge
    const int f = Layout::Force(N, i);
    mu(i) = (model_.force_hover_n(i) + scale_(f) * state_(f)) / nominal;
    d(i) = scale_(f) / nominal;
  }
  p_mu.template topLeftCorner<N, N>() =
      d.asDiagonal() * covariance_.template block<N, N>(Layout::Force(N, 0), Layout::Force(N, 0)) * d.asDiagonal();
  faults_.Update(utime, N, mu, p_mu);
}

template <int N>
void MultiArmLinearEstimator<N>::FillEstimate(const MultiArmStrainSample& sample, bool gated,
                                              MultiArmForceEstimate* estimate) {
  *estimate = MultiArmForceEstimate();
  estimate->utime = sample.utime;
  estimate->seq = sample.seq;
  estimate->n_rotors = N;
  double largest_std_n = 0.0;
  for (int i = 0; i < N; ++i) {
    const size_t k = static_cast<size_t>(i);
    const int f = Layout::Force(N, i);
    const double force = model_.force_hover_n(i) + scale_(f) * state_(f);
    force_std_n_[k] = scale_(f) * std::sqrt(std::max(covariance_(f, f), 0.0));
    estimate->force_n[k] = force;
    estimate->force_std_n[k] = force_std_n_[k];
    estimate->thrust_scale[k] = motor_.ThrustScale(i, force);
    largest_std_n = std::max(largest_std_n, force_std_n_[k]);
  }
  if (largest_std_n < noise_.converged_force_std_n) converged_ = true;
  facts_ = MultiArmFilterFacts();
  facts_.convergence = converged_ ? FilterConvergence::kConverged : FilterConvergence::kConverging;
  facts_.measurement_rejected = gated;
  faults_.FillFacts(N, &facts_);
  const MultiArmStatusBits bits = ComposeMultiArmFilterStatus(facts_, N);
  estimate->status = bits.status;
  estimate->rotor_fault_bits = bits.rotor_fault_bits;
}

template <int N>
void MultiArmLinearEstimator<N>::AddStrain(const MultiArmStrainSample& sample, MultiArmForceEstimate* estimate) {
  reports_.Open();
  motor_.Advance(sample.utime);
  bool gated = false;
  // At (re-)initialisation the state is set from the sample: fused, without an innovation.
  FusionReport strain = MakeFusionReport(FusionSource::kStrain, sample.utime, FusionOutcome::kFused);
  if (!initialized_) {
    Initialize(sample);
  } else {
    const double dt_s = static_cast<double>(sample.utime - last_utime_) * kMicrosecond;
    if (dt_s > 0) {
      // Whole strain periods (a gap of n samples is n periods; the pipeline
      // re-initialises after reset_gap_s), as LinearForceEstimator.
      Predict(std::max(1, static_cast<int>(std::lround(dt_s / model_.period_s))));
      last_utime_ = sample.utime;
    }
    UpdateGyro();
    strain = UpdateStrain(sample);
    gated = strain.outcome == FusionOutcome::kRejectedGate;
    if (!state_.allFinite() || !covariance_.allFinite()) {
      Initialize(sample);  // numerical failure: start again from this sample
      gated = false;
      strain = MakeFusionReport(FusionSource::kStrain, sample.utime, FusionOutcome::kFused);
    } else {
      UpdateFaults(sample.utime);
    }
  }
  reports_.Add(strain);
  reports_.Close();
  FillEstimate(sample, gated, estimate);
  // Held by the ground (or a stand) while the forces carry less than half
  // the hover's: the EKF's rule at rest (its thrust estimate below half the
  // weight) for a method without a contact model.
  double force_sum_n = 0.0, hover_sum_n = 0.0;
  for (int i = 0; i < N; ++i) {
    force_sum_n += estimate->force_n[static_cast<size_t>(i)];
    hover_sum_n += model_.force_hover_n(i);
  }
  supported_ = initialized_ && force_sum_n < kSupportedForceShare * hover_sum_n;
}

template class MultiArmLinearEstimator<2>;
template class MultiArmLinearEstimator<3>;
template class MultiArmLinearEstimator<4>;
template class MultiArmLinearEstimator<5>;
template class MultiArmLinearEstimator<6>;

namespace {

template <int N>
std::unique_ptr<MultiArmForceEstimator> MakeLinear(const VehicleDescription& vehicle, const EkfOptions& noise,
                                                   const LinearModelOptions& options,
                                                   const LuenbergerOptions* observer) {
  if (observer == nullptr) return std::make_unique<MultiArmLinearEstimator<N>>(vehicle, noise, options);
  return std::make_unique<MultiArmLinearEstimator<N>>(vehicle, noise, options, *observer);
}

}  // namespace

std::unique_ptr<MultiArmForceEstimator> MakeMultiArmLinearEstimator(const VehicleDescription& vehicle,
                                                                    const EkfOptions& noise,
                                                                    const LinearModelOptions& options,
                                                                    const LuenbergerOptions* observer) {
  switch (vehicle.arm_count) {
    case 2:
      return MakeLinear<2>(vehicle, noise, options, observer);
    case 3:
      return MakeLinear<3>(vehicle, noise, options, observer);
    case 4:
      return MakeLinear<4>(vehicle, noise, options, observer);
    case 5:
      return MakeLinear<5>(vehicle, noise, options, observer);
    case 6:
      return MakeLinear<6>(vehicle, noise, options, observer);
    default:
      return nullptr;
  }
}

}  // namespace birotor
