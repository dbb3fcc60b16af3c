// The EKF's fusions (members of EkfForceEstimator): each measurement model
// linearised at the prior and fused on the live states (LiveStates), in
// place on the blocks of x and P that the measurement reads, the rest of the
// live states through their cross covariance (UpdateTrailingStates): the
// strain with its gate and inflation, the telemetry, the gyro and the
// accelerometer (free flight only).
#include <algorithm>

#include "estimator/ekf_force_estimator.h"
#include "samples/rotor_count.h"

namespace birotor {

template <int N, int M, typename State, typename Cov>
FusionReport EkfForceEstimator::FuseOn(const MeasurementLinearization<M, N>& at,
                                       const Eigen::Matrix<double, M, M>& noise, const Eigen::Matrix<double, M, 1>& z,
                                       const FusionRequest& request, GateInflation inflation, State* x, Cov* cov) {
  if (inflation == GateInflation::kStrain) {
    // After gate_consecutive_limit rejections in a row the change is taken as
    // real (e.g. a lost propeller blade): the thrust scales open up
    // (var(mu_i) += inflation^2) and the sample is fused without the gate.
    const double extra = options_.gate_inflation_thrust_scale_std;
    return strain_gate_.Fuse(at, noise, z, request, x, cov, [extra](Cov* p) {
      for (int i = 0; i < 2; ++i) (*p)(kThrustScaleIndex[i], kThrustScaleIndex[i]) += extra * extra;
    });
  }
  if (inflation == GateInflation::kGyro) {
    // A pitch rate lost (a lift-off's transient): after as many gyro samples
    // gated in a row its variance grows by the initial one and the gyro is
    // fused ungated, as the linear methods do.
    const double extra = options_.initial_pitch_rate_std_rad_s;
    return gyro_gate_.Fuse(at, noise, z, request, x, cov,
                           [extra](Cov* p) { (*p)(kPitchRate, kPitchRate) += extra * extra; });
  }
  if (inflation == GateInflation::kAccelerometer) {
    // Strain scales learning: a total force the gauges' scales cannot give
    // (a softer arm: every accelerometer sample at the gate while g stays
    // at the file's) is taken as real after as many rejections in a row:
    // the thrust scales and the strain scales open up by their priors and
    // the sample is fused without the gate.
    const double mu_extra = options_.gate_inflation_thrust_scale_std, g_extra = options_.strain_scale_prior_std;
    return accel_gate_.Fuse(at, noise, z, request, x, cov, [mu_extra, g_extra](Cov* p) {
      for (int i = 0; i < 2; ++i) {
        (*p)(kThrustScaleIndex[i], kThrustScaleIndex[i]) += mu_extra * mu_extra;
        (*p)(kStrainScaleIndex[i], kStrainScaleIndex[i]) += g_extra * g_extra;
      }
    });
  }
  return FuseMeasurement(at, noise, z, request, x, cov);
}

template <int K, int N, int M>
FusionReport EkfForceEstimator::FuseRead(const MeasurementLinearization<M, kEkfStateSize>& at,
                                         const Eigen::Matrix<double, M, M>& noise, const Eigen::Matrix<double, M, 1>& z,
                                         const FusionRequest& request, GateInflation inflation) {
  static_assert(K <= N, "the measurement reads the leading K of the N live states");
  static_assert(kThrustScale1 < K && kThrustScale2 < K, "the inflation's states lead");
  auto x = state_.head<N>();
  auto cov = covariance_.topLeftCorner<N, N>();
  // With slow parameters live the covariance update sums its two last
  // corrections first (JosephForm::kCombined: half their cost, the same
  // product to round-off); with the offsets only (the shipped file) the two
  // products, to whose round-off the shipped figures are pinned.
  FusionRequest sized = request;
  if constexpr (N > kStrainScale1) {
    sized.joseph = JosephForm::kCombined;
    sized.consider_states = HeldStates(N);  // through a step or a lift-off
  }
  sized.consider_states |= OffsetsHeldNearGround();
  return FuseOn(LeadingStates<K>(at), noise, z, sized, inflation, &x, &cov);
}

template <int N, int M>
FusionReport EkfForceEstimator::FuseLive(const MeasurementLinearization<M, kEkfStateSize>& at,
                                         const Eigen::Matrix<double, M, M>& noise, const Eigen::Matrix<double, M, 1>& z,
                                         const FusionRequest& request, GateInflation inflation) {
  // The leading states H reads: its last non-zero column, rounded up to a
  // block boundary (the dynamic states, the offsets, the strain scales, the
  // body mass), at most the live ones.
  int read = 0;
  for (int j = kEkfStateSize - 1; j >= 0 && read == 0; --j) {
    if (!at.jacobian.col(j).isZero(0.0)) read = j + 1;
  }
  if (read <= kDynamicStateSize) return FuseRead<kDynamicStateSize, N>(at, noise, z, request, inflation);
  if (read <= kStrainScale1 || N == kStrainScale1) {
    return FuseRead<std::min(N, int{kStrainScale1}), N>(at, noise, z, request, inflation);
  }
  if (read <= kBodyMassScale || N == kBodyMassScale) {
    return FuseRead<std::min(N, int{kBodyMassScale}), N>(at, noise, z, request, inflation);
  }
  return FuseRead<N, N>(at, noise, z, request, inflation);
}

template <int M>
FusionReport EkfForceEstimator::Fuse(const MeasurementLinearization<M, kEkfStateSize>& at,
                                     const Eigen::Matrix<double, M, M>& noise, const Eigen::Matrix<double, M, 1>& z,
                                     const FusionRequest& request, GateInflation inflation) {
  // Only the live states (LiveStates: the rows and columns of P beyond them
  // are zero, and no fusion moves them), in place on the blocks of x and P.
  // The update on all 14 would give the same x and P (to round-off: sums
  // over zero terms) at up to (14/9)^2 the cost (issue 27: main was +16 %
  // per sample with learning off, +14 % with it on).
  switch (LiveStates()) {
    case kStrainScale1:
      return FuseLive<kStrainScale1>(at, noise, z, request, inflation);
    case kBodyMassScale:
      return FuseLive<kBodyMassScale>(at, noise, z, request, inflation);
    default:
      return FuseLive<kEkfStateSize>(at, noise, z, request, inflation);
  }
}

void EkfForceEstimator::ApplyMotor(const MotorSample& sample) {
  const bool late = sample.utime < last_utime_;
  if (TelemetryUsable(sample)) {
    if (late) {
      ReportNotFused(FusionSource::kTelemetry, sample.utime);
    } else {
      PredictTo(sample.utime);
      const MotorSpeedMeasurementModel::Vector z(sample.omega_meas_rad_s[0], sample.omega_meas_rad_s[1]);
      Report(Fuse(motor_model_.Linearize(state_), motor_model_.noise, z,
                  {FusionSource::kTelemetry, sample.utime, options_.telemetry_gate_nis}));
    }
  } else if (!late) {
    PredictTo(sample.utime);  // the previous command holds up to this stamp
  }
  for (int i = 0; i < 2; ++i) command_.omega_cmd_rad_s[i] = ClampCommand(params_, sample.omega_cmd_rad_s[i]);
  has_motor_ = true;
}

void EkfForceEstimator::ApplyImu(const ImuSample& sample) {
  if (sample.utime < last_utime_) {
    ReportImuNotFused(sample);
    return;
  }
  PredictTo(sample.utime);
  if (options_.use_gyro) {
    Report(Fuse(gyro_model_.Linearize(state_), gyro_model_.noise, GyroMeasurementModel::Vector(sample.gyro_y_rad_s),
                {FusionSource::kGyro, sample.utime, options_.gyro_gate_nis},
                GyroMayInflate(sample.utime) ? GateInflation::kGyro : GateInflation::kNone));
  }
  if (!options_.use_accelerometer || !AccelerometerUsable(sample)) return;
  if (options_.body_held || contact_.supported()) {
    // On the ground a_z is the support, not the thrust.
    ReportNotFused(FusionSource::kAccelerometer, sample.utime);
    return;
  }
  const AccelerometerMeasurementModel::Linearization at =
      accel_linearization_.valid ? AccelerometerMeasurementModel::Linearize(accel_linearization_, state_)
                                 : AccelerometerMeasurementModel::Linearize(process_, state_);
  Eigen::Matrix<double, 1, 1> noise = accel_model_.noise;
  // The noise learned online, its upper bound while few samples stand
  // behind it (NoiseAdaptation::CautiousScale; hover at 1 m/s^2, seed 3:
  // the worst 2 s window's 2-sigma share 0.772 with the scale as it was).
  noise(0, 0) *= accel_noise_.CautiousScale(0);
  noise(0, 0) += contact_.ReleasedSupportVarianceM2S4();  // the support that may still carry the body
  const FusionReport report = Fuse(at, noise, AccelerometerMeasurementModel::Vector(sample.accel_z_m_s2),
                                   {FusionSource::kAccelerometer, sample.utime, options_.accel_gate_nis},
                                   AccelerometerMayInflate() ? GateInflation::kAccelerometer : GateInflation::kNone);
  // From the first sample on (converged or not): a noisier accelerometer
  // would otherwise raise MODEL_MISMATCH before the filter converged. Held
  // in a thrust step (the strain gated, or fused after the gate's inflation,
  // within step_hold_s) and during a rotor fault: those innovations are the
  // step, not noise.
  accel_noise_.Add(report, &noise(0, 0), /*converged=*/true, faults_.AnyRotorFault() || InThrustStep());
  Report(report);
}

FusionReport EkfForceEstimator::FuseStrain(const StrainSample& sample) {
  const StrainMeasurementModel::Vector z(sample.deflection_rad[0], sample.deflection_rad[1]);
  return Fuse(strain_model_.Linearize(state_), strain_noise_rad2_, z,
              {FusionSource::kStrain, sample.utime, options_.strain_gate_nis}, GateInflation::kStrain);
}

}  // namespace birotor
