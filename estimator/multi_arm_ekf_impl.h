// The member definitions of MultiArmEkf<N> (estimator/multi_arm_ekf.h),
// included only by the one-N translation units estimator/multi_arm_ekf_n2.cc
// .. multi_arm_ekf_n6.cc, which instantiate it (and the model) for their N:
// the arm counts compile in parallel and a change rebuilds them alone.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "estimator/multi_arm_ekf.h"
#include "estimator/multi_arm_ekf_fusion.h"
#include "estimator/multi_arm_ekf_model_impl.h"
#include "estimator/multi_arm_offset_hold.h"

namespace birotor {
namespace multi_arm_ekf_detail {

constexpr double kMicrosecond = 1e-6;
// b_i of an arm without a reading at initialisation: 0 with this sigma [rad]
// (the static deflection at hover is f l / k ~ 1.4e-3 rad on the trirotor).
constexpr double kUnmeasuredDeflectionStdRad = 0.01;

}  // namespace multi_arm_ekf_detail

template <int N>
MultiArmEkf<N>::MultiArmEkf(const VehicleDescription& vehicle, const EkfOptions& options)
    : vehicle_(vehicle),
      options_(options),
      model_(vehicle),
      strain_gate_(options.gate_consecutive_limit),
      faults_(options),
      contact_(vehicle, options),
      strain_noise_(StrainNoiseSettings(options), N),
      accel_noise_(MultiArmAccelerometerNoiseSettings(options), 2) {
  strain_variance_rad2_.fill(options.strain_noise_rad * options.strain_noise_rad);
  process_noise_psd_.setZero();
  process_noise_psd_(Layout::kPitchRate) = options.pitch_rate_psd_rad2_s3;
  // The birotor EKF's numerical guards on the diagonal of P, per kind of
  // state (estimator/ekf_force_estimator.cc kVarianceFloor, kVarianceCeiling).
  floor_.setConstant(1e-12);  // phi_dot, b_dot [(rad/s)^2]
  ceiling_.setConstant(1e4);
  if (options.estimate_gauge_offsets && options.hold_unseen_offsets) offset_hold_ = UnseenOffsetHold<N>(vehicle);
  every_offset_hold_.active = options.estimate_gauge_offsets;
  every_offset_hold_.keep.setZero();
  for (int i = 0; i < N; ++i)
    has_arm_without_gauge_ = has_arm_without_gauge_ || !vehicle.arms[static_cast<size_t>(i)].has_gauge;
  const HoverSolution hover = SolveHover(vehicle);
  for (int i = 0; i < N; ++i) {
    const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
    process_noise_psd_(Layout::DeflectionRate(i)) = options.deflection_rate_psd_rad2_s3;
    process_noise_psd_(Layout::Omega(i)) = options.omega_psd_rad2_s;
    process_noise_psd_(Layout::ThrustScale(i)) = options.thrust_scale_psd_1_s;
    // The gauge reads s_i (b_i + e_i): a raw offset drift of q [rad^2/s] is q / s_i^2 in e_i.
    const double scale = arm.gauge_scale;
    const bool offsets = options.estimate_gauge_offsets && arm.has_gauge;
    process_noise_psd_(Layout::GaugeOffset(i)) = offsets ? vehicle.gauge_drift_psd_rad2_s / (scale * scale) : 0.0;
    offset_prior_std_[static_cast<size_t>(i)] = offsets ? vehicle.gauge_offset_std_rad / scale : 0.0;
    hover_input_.omega_cmd_rad_s[static_cast<size_t>(i)] =
        model_.ClampCommand(hover.omega_rad_s[static_cast<size_t>(i)]);
    floor_(Layout::Deflection(i)) = 1e-16;
    ceiling_(Layout::Deflection(i)) = 1e-2;
    floor_(Layout::Omega(i)) = 1e-6;
    ceiling_(Layout::Omega(i)) = 1e6;
    floor_(Layout::ThrustScale(i)) = 1e-10;
    ceiling_(Layout::ThrustScale(i)) = 4.0;
    floor_(Layout::GaugeOffset(i)) = offsets ? 1e-16 : 0.0;
    ceiling_(Layout::GaugeOffset(i)) = 1e-6;
  }
  Reset();
}

template <int N>
void MultiArmEkf<N>::Reset() {
  initialized_ = false;
  converged_ = false;
  has_motor_ = false;
  command_ = hover_input_;
  accel_linearization_valid_ = false;
  while (!motor_queue_.empty()) motor_queue_.pop();
  while (!imu_queue_.empty()) imu_queue_.pop();
  strain_gate_.Reset();
  faults_.Reset();
  contact_.Reset();
  ground_carry_ = false;
  state_.setZero();
  covariance_.setZero();
  force_std_n_.fill(std::numeric_limits<double>::infinity());
  facts_ = MultiArmFilterFacts();
  reports_.clear();
}

template <int N>
void MultiArmEkf<N>::SetGaugeOffsetPrior(const double* offset_std_rad) {
  for (int i = 0; i < N; ++i) {
    const size_t k = static_cast<size_t>(i);
    if (offset_prior_std_[k] > 0) offset_prior_std_[k] = offset_std_rad[i];  // only where offsets are states
  }
}

template <int N>
bool MultiArmEkf<N>::LearnedGaugeOffset(int arm, double* offset_rad, double* std_rad) const {
  if (!initialized_ || arm < 0 || arm >= N || !(offset_prior_std_[static_cast<size_t>(arm)] > 0)) return false;
  const int e = Layout::GaugeOffset(arm);
  *offset_rad = state_(e);
  *std_rad = std::sqrt(std::max(covariance_(e, e), 0.0));
  return true;
}

template <int N>
void MultiArmEkf<N>::AddMotor(const MultiArmMotorSample& sample) {
  MultiArmMotorSample dropped;
  motor_queue_.push(sample, &dropped);
}

template <int N>
void MultiArmEkf<N>::AddImu(const ImuSample& sample) {
  // Ground contact on arrival, with the thrusts of the current estimate (the
  // weight before the first strain sample), as the birotor's EKF: it selects
  // the model of the next predictions.
  std::array<double, N> force_n{};
  for (int i = 0; i < N && initialized_; ++i) force_n[static_cast<size_t>(i)] = model_.Force(state_, i);
  contact_.Update(sample.utime, sample.accel_z_m_s2, initialized_ ? force_n.data() : nullptr);
  if (!options_.use_gyro && !options_.use_accelerometer) return;
  ImuSample dropped;
  imu_queue_.push(sample, &dropped);
}

template <int N>
void MultiArmEkf<N>::CalibratedStrain(const MultiArmStrainSample& sample, Eigen::Matrix<double, N, 1>* z,
                                      Measured* measured) const {
  for (int i = 0; i < N; ++i) {
    const ArmDescription& arm = vehicle_.arms[static_cast<size_t>(i)];
    const double raw = sample.deflection_rad[static_cast<size_t>(i)];
    // The description's calibration: the gauge reads s_i b_i + o_i.
    const double calibrated = (raw - arm.gauge_offset_rad) / arm.gauge_scale;
    (*measured)[static_cast<size_t>(i)] = sample.n_arms == N && arm.has_gauge && std::isfinite(calibrated);
    (*z)(i) = (*measured)[static_cast<size_t>(i)] ? calibrated : 0.0;
  }
}

template <int N>
void MultiArmEkf<N>::Initialize(const MultiArmStrainSample& sample) {
  // Commands stamped up to the sample: the newest holds, the newest finite
  // telemetry sets omega_i (else the command, else the hover speed). Offsets
  // e = 0 with their prior sigma, b = z - e (var b = R + var e, cov(b, e) =
  // -var e), rates 0, mu = 1 with initial_thrust_scale_std.
  std::array<double, N> telemetry{};
  std::array<bool, N> has_telemetry{};
  while (!motor_queue_.empty() && motor_queue_.front().utime <= sample.utime) {
    const MultiArmMotorSample& m = motor_queue_.front();
    for (int i = 0; i < N && m.n_rotors == N; ++i) {
      const size_t k = static_cast<size_t>(i);
      command_.omega_cmd_rad_s[k] = model_.ClampCommand(m.omega_cmd_rad_s[k]);
      has_motor_ = true;
      if (options_.use_motor_telemetry && std::isfinite(m.omega_meas_rad_s[k])) {
        telemetry[k] = m.omega_meas_rad_s[k];
        has_telemetry[k] = true;
      }
    }
    motor_queue_.pop();
  }
  while (!imu_queue_.empty() && imu_queue_.front().utime <= sample.utime) imu_queue_.pop();
  Eigen::Matrix<double, N, 1> z;
  Measured measured;
  CalibratedStrain(sample, &z, &measured);
  state_.setZero();
  covariance_.setZero();
  for (int i = 0; i < N; ++i) {
    const size_t k = static_cast<size_t>(i);
    const double r = strain_variance_rad2_[k];  // the learned noise: it is the gauge's
    const int b = Layout::Deflection(i), e = Layout::GaugeOffset(i), w = Layout::Omega(i), m = Layout::ThrustScale(i);
    const double offset_variance = offset_prior_std_[k] * offset_prior_std_[k];
    state_(b) = measured[k] ? z(i) : 0.0;
    covariance_(b, b) = measured[k] ? r + offset_variance
                                    : multi_arm_ekf_detail::kUnmeasuredDeflectionStdRad *
                                          multi_arm_ekf_detail::kUnmeasuredDeflectionStdRad;
    if (measured[k]) covariance_(b, e) = covariance_(e, b) = -offset_variance;
    covariance_(e, e) = offset_variance;
    state_(w) = has_telemetry[k] ? telemetry[k] : command_.omega_cmd_rad_s[k];
    state_(m) = 1.0;
    const double rate_std = options_.initial_deflection_rate_std_rad_s;
    covariance_(Layout::DeflectionRate(i), Layout::DeflectionRate(i)) = rate_std * rate_std;
    // Without any MOTOR sample omega is the assumed hover speed: known no better than that speed itself.
    const double omega_std = has_motor_ ? options_.initial_omega_std_rad_s
                                        : std::max(options_.initial_omega_std_rad_s, hover_input_.omega_cmd_rad_s[k]);
    covariance_(w, w) = omega_std * omega_std;
    covariance_(m, m) = options_.initial_thrust_scale_std * options_.initial_thrust_scale_std;
  }
  const double pitch_std = options_.initial_pitch_rate_std_rad_s;
  covariance_(Layout::kPitchRate, Layout::kPitchRate) = pitch_std * pitch_std;
  strain_gate_.Reset();
  strain_noise_.BreakSequence();
  accel_noise_.BreakSequence();
  converged_ = false;
  faults_.Reset();
  accel_linearization_valid_ = false;
  last_utime_ = sample.utime;
  initialized_ = true;
}

template <int N>
void MultiArmEkf<N>::PredictTo(int64_t utime) {
  if (utime <= last_utime_) return;
  const double dt_s = static_cast<double>(utime - last_utime_) * multi_arm_ekf_detail::kMicrosecond;
  // Equal sub-steps no longer than max_prediction_step_s (one at the nominal 1 kHz).
  const int steps = std::max(1, static_cast<int>(std::ceil(dt_s / options_.max_prediction_step_s - 1e-9)));
  const double step_s = dt_s / steps;
  Input input = command_;
  input.supported = contact_.supported();
  for (int k = 0; k < steps; ++k) Predict(step_s, input);
  last_utime_ = utime;
}

template <int N>
void MultiArmEkf<N>::Predict(double dt_s, const Input& input) {
  // Linearise at the prior; x by RK4; P = Phi P Phi^T + Qc dt with
  // Phi = [I, 0; 0, Phi_d] (the offsets, first, are random walks).
  constexpr int n = Layout::kDynamicSize, m = N, first = Layout::kFirstDynamic;
  // RK4's first stage f(x, u) comes with the Jacobian (the same solve).
  State x_dot;
  const typename Model::DynamicMatrix a = model_.Jacobian(state_, input, &accel_linearization_, &x_dot);
  accel_linearization_valid_ = !input.supported;  // the held body's Jacobian has none
  // Phi_d has A's block structure when Transition took it: products on its blocks.
  bool blocks = false;
  const typename Model::DynamicMatrix phi = Model::Transition(a, dt_s, &blocks);
  state_ = model_.StepFrom(state_, x_dot, input, dt_s);
  auto p_dd = covariance_.template block<n, n>(first, first);
  p_dd = Model::Propagate(phi, p_dd, blocks);
  const Eigen::Matrix<double, n, m> p_de =
      Model::template TransitionTimes<m>(phi, covariance_.template block<n, m>(first, 0), blocks);
  covariance_.template block<n, m>(first, 0) = p_de;
  covariance_.template block<m, n>(0, first) = p_de.transpose();
  covariance_.diagonal() += process_noise_psd_ * dt_s;
}

template <int N>
void MultiArmEkf<N>::ApplyQueuedUpTo(int64_t utime) {
  DrainInTimeOrder(
      utime, &motor_queue_, &imu_queue_, [this](const MultiArmMotorSample& sample) { ApplyMotor(sample); },
      [this](const ImuSample& sample) { ApplyImu(sample); });
}

template <int N>
void MultiArmEkf<N>::ApplyMotor(const MultiArmMotorSample& sample) {
  if (sample.n_rotors != N) return;  // another vehicle's stream: not this filter's input
  if (sample.utime >= last_utime_) {
    PredictTo(sample.utime);  // the previous command holds up to this stamp
    Measured measured;
    Eigen::Matrix<double, N, 1> z;
    bool any = false;
    for (int i = 0; i < N; ++i) {
      const double omega = sample.omega_meas_rad_s[static_cast<size_t>(i)];
      measured[static_cast<size_t>(i)] = options_.use_motor_telemetry && std::isfinite(omega);
      z(i) = measured[static_cast<size_t>(i)] ? omega : 0.0;
      any = any || measured[static_cast<size_t>(i)];
    }
    if (any) {
      using Measurements = MultiArmMeasurements<N>;
      // Telemetry reads omega_i alone: H's rows are unit rows (multi_arm_ekf_fusion.h).
      FusionReport report = MakeFusionReport(FusionSource::kTelemetry, sample.utime, FusionOutcome::kNotFused);
      FuseOnesRowsUnreported(Measurements::Telemetry(state_, measured),
                             Measurements::MaskedNoise(options_.motor_speed_noise_rad_s, measured), z,
                             options_.telemetry_gate_nis, &state_, &covariance_, nullptr, &report, FlightOffsetHold(),
                             GroundThrustScaleHold());
      LeaveOutUnmeasured(measured, &report);
      reports_.Add(report);
    }
  }
  for (int i = 0; i < N; ++i) {
    const size_t k = static_cast<size_t>(i);
    const double cmd = sample.omega_cmd_rad_s[k];
    if (std::isfinite(cmd)) command_.omega_cmd_rad_s[k] = model_.ClampCommand(cmd);
  }
  has_motor_ = true;
}

template <int N>
void MultiArmEkf<N>::ApplyImu(const ImuSample& sample) {
  if (sample.utime < last_utime_) return;
  PredictTo(sample.utime);
  using Measurements = MultiArmMeasurements<N>;
  if (options_.use_gyro && std::isfinite(sample.gyro_y_rad_s)) {
    const auto gyro = Measurements::Gyro(state_);
    Eigen::Matrix<double, 1, 1> r(options_.gyro_noise_rad_s * options_.gyro_noise_rad_s);
    r(0, 0) += contact_.HeldRateVariance(gyro.predicted(0));  // a touch may hold the body still
    FusionReport report = MakeFusionReport(FusionSource::kGyro, sample.utime, FusionOutcome::kNotFused);
    FuseOnesRowsUnreported(gyro, r, Eigen::Matrix<double, 1, 1>(sample.gyro_y_rad_s), options_.gyro_gate_nis, &state_,
                           &covariance_, nullptr, &report, FlightOffsetHold(),
                           GroundThrustScaleHold());  // a unit row: phi_dot
    reports_.Add(report);
  }
  const bool accel_finite = std::isfinite(sample.accel_x_m_s2) && std::isfinite(sample.accel_z_m_s2);
  // On the ground a_z is the support, not the thrust: not fused (the birotor's rule).
  if (!options_.use_accelerometer || !accel_finite || !accel_linearization_valid_ || contact_.supported()) return;
  const double file_m2s4 = options_.accel_noise_m_s2 * options_.accel_noise_m_s2;
  // R of (a_x, a_z): the file's variance times each learned scale (a_z is
  // the report's component 0), a_z's widened by the support that may still
  // carry the body [m^2/s^4].
  Eigen::Matrix2d r = Eigen::Matrix2d::Zero();
  r(0, 0) = accel_noise_.scale(1) * file_m2s4;
  r(1, 1) = accel_noise_.scale(0) * file_m2s4 + contact_.ReleasedSupportVarianceM2S4();
  // H's first N columns (the offsets e_i) are zero: left out. Fused with
  // the scales as they stand (not the birotor's upper bound until trusted,
  // NoiseAdaptation::CautiousScale: within 0.03 of these figures on the
  // noisy hovers of docs/estimator.md), and at an airborne start only once
  // the scales were learned from accel_noise_min_samples pairs (starting at
  // their median: MultiArmAccelerometerNoiseSettings): before, the
  // gate is 0 (rejected, and learned from as gated samples are). Fused at
  // the file's variance, the first samples of a frame 20x noisier than its
  // file pulled the thrust scales far enough to flag a rotor fault, which
  // froze the learning at a_z's scale 38 of 400 for a second (the trirotor
  // hovering with accel_noise_m_s2 1.0, seed 8), or left rotors 2 and 3
  // 0.7 N off at a 2-sigma share of 0.03 from 0.5 to 1.5 s (seed 7). After
  // a time on the ground the lift-off is read at once (a payload's
  // evidence; its thrust step holds the learning, and the accelerometer
  // left out that long let a drifting gauge's offset run on the N = 2
  // description without arm 1's gauge). docs/estimator.md, "The
  // accelerometer's noise".
  const bool unlearned_in_air = accel_noise_.enabled() && accel_noise_.samples() < options_.accel_noise_min_samples &&
                                !contact_.has_been_supported();
  FusionReport report = MakeFusionReport(FusionSource::kAccelerometer, sample.utime, FusionOutcome::kNotFused);
  FuseSymmetricUnreported<Layout::kFirstDynamic>(
      Measurements::Accelerometer(accel_linearization_, state_), r,
      Eigen::Vector2d(sample.accel_x_m_s2, sample.accel_z_m_s2), unlearned_in_air ? 0.0 : options_.accel_gate_nis,
      &state_, &covariance_, nullptr, &report, AccelerometerOffsetHold(), GroundThrustScaleHold());
  // a_z first: the thrust axis, the birotor's accelerometer report (its
  // one component), which the model-consistency monitor's fast test reads.
  std::swap(report.innovation(0), report.innovation(1));
  std::swap(report.innovation_variance(0), report.innovation_variance(1));
  // From the first sample on, as the birotor's (ekf_fusion.cc ApplyImu);
  // held (accel_noise_hold_s) from a thrust step, which gates the strain
  // first, and during a rotor fault: those innovations are not noise.
  const double r_used[2] = {r(1, 1), r(0, 0)};
  const bool thrust_step = strain_gate_.consecutive_rejected() > 0;
  accel_noise_.Add(report, r_used, /*converged=*/true, AnyRotorFault() || thrust_step);
  reports_.Add(report);
}

template <int N>
void MultiArmEkf<N>::LeaveOutUnmeasured(const Measured& measured, FusionReport* report) {
  for (int i = 0; i < N; ++i) {
    if (!measured[static_cast<size_t>(i)]) report->innovation_variance(i) = 0.0;
  }
}

template <int N>
Eigen::Matrix<double, N, N> MultiArmEkf<N>::StrainNoise(const Measured& measured) const {
  // MaskedNoise's 1 on a masked entry, R_i on a measured one.
  Eigen::Matrix<double, N, N> r = Eigen::Matrix<double, N, N>::Zero();
  for (int i = 0; i < N; ++i) {
    const size_t k = static_cast<size_t>(i);
    r(i, i) = measured[k] ? strain_variance_rad2_[k] : 1.0;
  }
  return r;
}

template <int N>
bool MultiArmEkf<N>::AnyRotorFault() const {
  bool fault = false;
  for (int i = 0; i < N; ++i) fault = fault || faults_.fault(i);
  return fault;
}

template <int N>
void MultiArmEkf<N>::LearnStrainNoise(const FusionReport& strain) {
  if (!strain_noise_.Add(strain, strain_variance_rad2_.data(), converged_, AnyRotorFault())) return;
  const double file_rad2 = options_.strain_noise_rad * options_.strain_noise_rad;
  for (int i = 0; i < N; ++i) strain_variance_rad2_[static_cast<size_t>(i)] = strain_noise_.scale(i) * file_rad2;
}

template <int N>
FusionReport MultiArmEkf<N>::FuseStrain(const MultiArmStrainSample& sample) {
  Eigen::Matrix<double, N, 1> z;
  Measured measured;
  CalibratedStrain(sample, &z, &measured);
  using Measurements = MultiArmMeasurements<N>;
  // After gate_consecutive_limit rejections in a row the change is taken as
  // real (a lost propeller blade): var(mu_i) += inflation^2, fused ungated.
  const double extra = options_.gate_inflation_thrust_scale_std;
  // The strain reads b_i + e_i: H's rows are sums of two unit rows (multi_arm_ekf_fusion.h).
  const MeasurementLinearization<N, Layout::kStateSize> at = Measurements::Strain(state_, measured);
  const Eigen::Matrix<double, N, N> noise = StrainNoise(measured);
  FusionReport report = MakeFusionReport(FusionSource::kStrain, sample.utime, FusionOutcome::kNotFused);
  strain_gate_.FuseUnreportedWith(
      options_.strain_gate_nis,
      [&](double gate) {
        return FuseOnesRowsUnreported(at, noise, z, gate, &state_, &covariance_, nullptr, &report, FlightOffsetHold(),
                                      GroundThrustScaleHold());
      },
      &covariance_,
      [extra](Covariance* p) {
        for (int i = 0; i < N; ++i) (*p)(Layout::ThrustScale(i), Layout::ThrustScale(i)) += extra * extra;
      },
      &report.fused_after_inflation);
  report.gate = options_.strain_gate_nis;  // the gate, also when fused after the inflation
  LeaveOutUnmeasured(measured, &report);
  return report;
}

template <int N>
bool MultiArmEkf<N>::ConditionCovariance() {
  if (!state_.allFinite() || !covariance_.allFinite()) return false;
  // P is exactly symmetric here, no (P + P^T) / 2 needed: every step writes
  // each pair (r, c), (c, r) once (Initialize; MultiArmEkfModel::Propagate and
  // Predict's cross block; every fusion's SymmetricJosephUpdate; the
  // diagonal's noise and inflation; the row-and-column scaling below).
  // tests/estimator/multi_arm_ekf_test.cc asserts P == P^T after a flight.
  for (int i = 0; i < Layout::kStateSize; ++i) {
    const double variance = covariance_(i, i);
    if (variance < -1e-6 * ceiling_(i)) return false;  // clearly negative: broken
    if (variance < floor_(i)) {
      covariance_(i, i) = floor_(i);
    } else if (variance > ceiling_(i)) {
      // Scale row and column: keeps P positive semi-definite.
      const double s = std::sqrt(ceiling_(i) / variance);
      covariance_.row(i) *= s;
      covariance_.col(i) *= s;
    }
  }
  for (int i = 0; i < N; ++i) {
    const double mu = state_(Layout::ThrustScale(i));
    if (mu < -1.0 || mu > 5.0 || state_(Layout::Omega(i)) < -1e3) return false;
  }
  return true;
}

template <int N>
void MultiArmEkf<N>::UpdateFaults(int64_t utime) {
  MultiArmFaultMonitor::ScaleVector mu = MultiArmFaultMonitor::ScaleVector::Zero();
  MultiArmFaultMonitor::ScaleMatrix p_mu = MultiArmFaultMonitor::ScaleMatrix::Zero();
  mu.template head<N>() = state_.template segment<N>(Layout::ThrustScale(0));
  p_mu.template topLeftCorner<N, N>() =
      covariance_.template block<N, N>(Layout::ThrustScale(0), Layout::ThrustScale(0));
  faults_.Update(utime, N, mu, p_mu);
}

template <int N>
void MultiArmEkf<N>::AddStrain(const MultiArmStrainSample& sample, MultiArmForceEstimate* estimate) {
  bool gated = false;
  reports_.clear();
  if (!initialized_) {
    Initialize(sample);
  } else {
    ApplyQueuedUpTo(sample.utime);
    PredictTo(sample.utime);
    const FusionReport strain = FuseStrain(sample);
    gated = strain.outcome == FusionOutcome::kRejectedGate;
    if (!ConditionCovariance()) {
      Initialize(sample);  // numerical failure: start again from this sample
      gated = false;
    } else {
      reports_.Add(strain);
      UpdateFaults(sample.utime);
      LearnStrainNoise(strain);
    }
  }
  FillEstimate(sample, gated, estimate);
}

template <int N>
void MultiArmEkf<N>::FillEstimate(const MultiArmStrainSample& sample, bool gated, MultiArmForceEstimate* estimate) {
  *estimate = MultiArmForceEstimate();
  estimate->utime = sample.utime;
  estimate->seq = sample.seq;
  estimate->n_rotors = N;
  double largest_std_n = 0.0;
  for (int i = 0; i < N; ++i) {
    const size_t k = static_cast<size_t>(i);
    // var f_i = g^T P_(omega_i, mu_i) g with g = (df/domega, df/dmu).
    const Eigen::Vector2d grad = model_.ForceGradient(state_, i);
    const int w = Layout::Omega(i), m = Layout::ThrustScale(i);
    const double variance = grad(0) * grad(0) * covariance_(w, w) + 2.0 * grad(0) * grad(1) * covariance_(w, m) +
                            grad(1) * grad(1) * covariance_(m, m);
    force_std_n_[k] = std::sqrt(std::max(variance, 0.0));
    estimate->force_n[k] = model_.Force(state_, i);
    estimate->force_std_n[k] = force_std_n_[k];
    estimate->thrust_scale[k] = state_(m);
    largest_std_n = std::max(largest_std_n, force_std_n_[k]);
  }
  if (largest_std_n < options_.converged_force_std_n) converged_ = true;
  facts_ = MultiArmFilterFacts();
  facts_.convergence = converged_ ? FilterConvergence::kConverged : FilterConvergence::kConverging;
  facts_.measurement_rejected = gated;
  faults_.FillFacts(N, &facts_);
  const MultiArmStatusBits bits = ComposeMultiArmFilterStatus(facts_, N);
  estimate->status = bits.status;
  estimate->rotor_fault_bits = bits.rotor_fault_bits;
}

}  // namespace birotor
