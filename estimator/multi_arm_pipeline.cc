#include "estimator/multi_arm_pipeline.h"

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "estimator/estimation_method.h"
#include "model/multi_arm_linearization.h"

namespace birotor {
namespace {

bool FiniteWithin(double value, double limit) { return std::isfinite(value) && std::abs(value) <= limit; }

bool IsFinite(const MultiArmForceEstimate& e) {
  for (int i = 0; i < e.n_rotors; ++i) {
    const size_t k = static_cast<size_t>(i);
    if (!std::isfinite(e.force_n[k]) || !std::isfinite(e.force_std_n[k]) || !std::isfinite(e.thrust_scale[k])) {
      return false;
    }
  }
  return true;
}

// The N-arm pipeline's notches: the birotor's options at multi_arm_bandwidth_hz.
HarmonicNotchOptions MultiArmNotchOptions(const HarmonicNotchOptions& options) {
  HarmonicNotchOptions narrow = options;
  narrow.bandwidth_hz = options.multi_arm_bandwidth_hz;
  return narrow;
}

// The arm mode over every arm's tip mass when it is learned: switched on, a
// method that flies m_p (the EKF), and a mode the test reads.
ArmModeTipMassMap TipMassMapOf(const EstimatorConfig& config, const MultiArmForceEstimator& filter,
                               const ArmModeExpectation& arm_mode) {
  const ModelConsistencyOptions& options = config.model_consistency;
  const bool learns = options.enabled && options.arm_mode_enabled && options.arm_mode_learn_tip_mass &&
                      filter.flies_tip_mass() && arm_mode.file_hz > 0;
  return learns ? ArmModeTipMassMap::Of(config.vehicle, arm_mode.mode_index) : ArmModeTipMassMap();
}

// The monitor's options for N arms: the arm-mode test's own excitation bar.
ModelConsistencyOptions MultiArmConsistencyOptions(const ModelConsistencyOptions& options) {
  ModelConsistencyOptions n_arms = options;
  n_arms.arm_mode_min_excitation = options.arm_mode_multi_arm_min_excitation;
  return n_arms;
}

// How each gauge's raw reading moves when the vehicle weighs more (the
// offset-departure test's direction, estimator/offset_departure.h): s_i
// times the hover deflection with 10 % more body mass minus the file's, the
// thrusts shared as the hover allocation shares the weight; 0 on an arm
// without a gauge, whose offset is no state and cannot take a force (its
// anchor's sigma would only dilute the departure) [rad]; and the
// force that payload adds to each rotor, which is what a departure of one
// direction would be (offset_departure_in_sigma_above) [N].
struct CommonForce {
  ArmValues readings{};
  ArmValues force_n{};
};

CommonForce CommonForceReadings(const VehicleDescription& vehicle) {
  VehicleDescription heavier = vehicle;
  heavier.body_mass_kg *= 1.1;
  const MultiArmHover file = SolveMultiArmHover(vehicle), payload = SolveMultiArmHover(heavier);
  CommonForce common;
  for (int i = 0; i < vehicle.arm_count; ++i) {
    const size_t k = static_cast<size_t>(i);
    const double moved_rad = payload.deflection_rad(i) - file.deflection_rad(i);
    common.readings[k] = vehicle.arms[k].has_gauge ? vehicle.arms[k].gauge_scale * moved_rad : 0.0;
    common.force_n[k] = payload.force_n(i) - file.force_n(i);
  }
  return common;
}

}  // namespace

MultiArmPipeline::MultiArmPipeline(const EstimatorConfig& config)
    : config_(config),
      filter_(MakeMultiArmForceEstimator(config)),
      // The arm-mode test on the vehicle's most readable arm mode, learning every arm's tip mass from it.
      arm_mode_(ExpectedArmMode(config.vehicle)),
      consistency_(MultiArmConsistencyOptions(config.model_consistency), arm_mode_, config.ekf.strain_noise_rad,
                   config.vehicle.arm_count, TipMassMapOf(config, *filter_, arm_mode_)),
      admission_(config.pipeline),
      notch_on_(config.harmonic_notch.enabled && config.harmonic_notch.multi_arm_enabled),
      rotor_speed_(config.vehicle, config.pipeline.motor_timeout_s),
      notch_(MultiArmNotchOptions(config.harmonic_notch), config.vehicle.arm_count) {
  for (int i = 0; i < kNumInputChannels; ++i) {
    FusionSource source;
    const bool gated = GatedSourceOf(static_cast<InputChannel>(i), &source);
    health_.inputs[i].gate = gated ? filter_->Gate(source) : std::numeric_limits<double>::quiet_NaN();
  }
  health_.accelerometer.gate = filter_->Gate(FusionSource::kAccelerometer);
  health_.strain_noise_learned = filter_->learns_strain_noise();
  calibration_.arm_count = config.vehicle.arm_count;
  for (int i = 0; i < config.vehicle.arm_count; ++i) {
    const size_t k = static_cast<size_t>(i);
    calibration_.offset_rad[k] = config.vehicle.arms[k].gauge_offset_rad;
    calibration_.offset_std_rad[k] = config.vehicle.gauge_offset_std_rad;
  }
  ArmValues drift_psd_rad2_s;
  drift_psd_rad2_s.fill(config.vehicle.gauge_drift_psd_rad2_s);
  const CommonForce common = CommonForceReadings(config.vehicle);
  consistency_.SetOffsetGauges(common.readings.data(), drift_psd_rad2_s.data(), common.force_n.data());
  consistency_.AnchorOffsets(calibration_.offset_rad.data(), calibration_.offset_std_rad.data());
}

void MultiArmPipeline::ResumeGaugeState(const MultiArmGaugeState& state) {
  if (state.arm_count != config_.vehicle.arm_count) return;
  double prior_std_rad[kMaxSampleArms] = {};  // in deflection: o_i / s_i
  for (int i = 0; i < state.arm_count; ++i) {
    const size_t k = static_cast<size_t>(i);
    calibration_.offset_rad[k] = state.offset_rad[k];
    calibration_.offset_std_rad[k] = state.offset_std_rad[k];
    prior_std_rad[k] = state.offset_std_rad[k] / config_.vehicle.arms[k].gauge_scale;
  }
  calibration_.source = state.source;
  health_.gauge_offset_source = state.source;
  offsets_resumed_ = true;
  filter_->SetGaugeOffsetPrior(prior_std_rad);
  consistency_.AnchorOffsets(calibration_.offset_rad.data(), calibration_.offset_std_rad.data());
  if (state.has_tip_mass) ResumeTipMass(state.tip_mass_ratio, state.tip_mass_ratio_std);
}

MultiArmGaugeState MultiArmPipeline::GaugeState() const {
  MultiArmGaugeState state = calibration_;
  OffsetsInUse(&state.offset_rad, &state.offset_std_rad);
  const OffsetDepartureState& departure = consistency_.state().offsets;
  for (int i = 0; i < state.arm_count && departure.departed; ++i) {
    // They took a force (a payload): the next start keeps the anchor they left.
    const size_t k = static_cast<size_t>(i);
    state.offset_rad[k] = departure.anchor_rad[k];
    state.offset_std_rad[k] = departure.anchor_std_rad[k];
  }
  state.has_tip_mass = health_.tip_mass_learned;
  state.tip_mass_ratio = health_.tip_mass_ratio;
  state.tip_mass_ratio_std = health_.tip_mass_ratio_std;
  return state;
}

void MultiArmPipeline::ResumeTipMass(double ratio, double ratio_std) {
  // The arm-mode test learns the map's m_p, the arms' mean m_p,i; with its
  // learning off (or no mode to learn from) the description's m_p,i are flown.
  const double mean_kg = ArmModeTipMassMap::MeanTipMassKg(config_.vehicle);
  if (!consistency_.ResumeTipMass(ratio * mean_kg, ratio_std * mean_kg)) return;
  const ArmModeState& arm_mode = consistency_.state().arm_mode;
  health_.tip_mass_learned = true;
  health_.tip_mass_from_state_file = true;
  health_.tip_mass_ratio = arm_mode.tip_mass_kg / mean_kg;
  health_.tip_mass_ratio_std = arm_mode.tip_mass_std_kg / mean_kg;
  filter_->SetTipMassScale(health_.tip_mass_ratio);  // flown from the first sample (a reset keeps it)
  tip_mass_ratio_in_filter_ = health_.tip_mass_ratio;
}

bool MultiArmPipeline::Admit(InputChannel channel, int64_t utime, int32_t seq, Admission* admission) {
  *admission = admission_.Admit(channel, utime, seq, health_.inputs);
  health_.newest_utime = admission_.newest_utime();
  return IsAccepted(*admission);
}

bool MultiArmPipeline::ValidStrain(const MultiArmStrainSample& sample) const {
  if (sample.n_arms != config_.vehicle.arm_count) return false;
  const double limit = config_.pipeline.max_deflection_rad;
  for (int i = 0; i < sample.n_arms; ++i) {
    const double b = sample.deflection_rad[static_cast<size_t>(i)];
    if (!std::isnan(b) && !FiniteWithin(b, limit)) return false;  // NaN: no reading of that arm
  }
  return true;
}

bool MultiArmPipeline::ValidMotor(const MultiArmMotorSample& sample) const {
  if (sample.n_rotors != config_.vehicle.arm_count) return false;
  const double limit = config_.pipeline.max_omega_rad_s;
  for (int i = 0; i < sample.n_rotors; ++i) {
    const size_t k = static_cast<size_t>(i);
    if (!FiniteWithin(sample.omega_cmd_rad_s[k], limit)) return false;
    if (!std::isnan(sample.omega_meas_rad_s[k]) && !FiniteWithin(sample.omega_meas_rad_s[k], limit)) return false;
  }
  return true;
}

void MultiArmPipeline::OnMotor(const MultiArmMotorSample& sample) {
  InputCounters& c = health_.inputs[static_cast<int>(InputChannel::kMotor)];
  if (!ValidMotor(sample)) {
    ++c.rejected_invalid;
    return;
  }
  Admission admission;
  if (!Admit(InputChannel::kMotor, sample.utime, sample.seq, &admission)) return;
  for (int i = 0; i < sample.n_rotors; ++i) {
    if (std::isnan(sample.omega_meas_rad_s[static_cast<size_t>(i)])) {
      ++c.reading_missing;
      break;
    }
  }
  if (!has_motor_) first_motor_utime_ = sample.utime;
  last_motor_ = sample;
  has_motor_ = true;
  rotor_speed_.AddMotor(sample);
  filter_->AddMotor(sample);
}

void MultiArmPipeline::OnImu(const ImuSample& sample) {
  InputCounters& c = health_.inputs[static_cast<int>(InputChannel::kImu)];
  if (!FiniteWithin(sample.gyro_y_rad_s, config_.pipeline.max_gyro_rad_s)) {
    ++c.rejected_invalid;
    return;
  }
  Admission admission;
  if (!Admit(InputChannel::kImu, sample.utime, sample.seq, &admission)) return;
  if (!std::isfinite(sample.accel_x_m_s2) || !std::isfinite(sample.accel_z_m_s2)) ++c.reading_missing;
  if (std::isfinite(sample.accel_z_m_s2)) CountAccelerometerSample(sample.utime, sample.seq, &health_.accelerometer);
  filter_->AddImu(sample);
}

void MultiArmPipeline::OnPose(const PoseSample& sample) {
  InputCounters& c = health_.inputs[static_cast<int>(InputChannel::kPose)];
  if (!std::isfinite(sample.x_m) || !std::isfinite(sample.z_m) || !std::isfinite(sample.phi_rad)) {
    ++c.rejected_invalid;
    return;
  }
  Admission admission;
  if (!Admit(InputChannel::kPose, sample.utime, sample.seq, &admission)) return;
  filter_->AddPose(sample);
}

bool MultiArmPipeline::OnStrain(const MultiArmStrainSample& sample, MultiArmForceEstimate* estimate) {
  InputCounters& c = health_.inputs[static_cast<int>(InputChannel::kStrain)];
  if (!ValidStrain(sample)) {
    ++c.rejected_invalid;
    return false;
  }
  const int64_t previous_utime = c.last_utime;
  Admission admission;
  if (!Admit(InputChannel::kStrain, sample.utime, sample.seq, &admission)) return false;
  const bool backwards = admission == Admission::kAcceptedBackwardsJump;
  const bool stale = CheckStrainTiming(sample.utime, previous_utime, backwards);
  const MultiArmStrainSample deflection = Condition(sample, previous_utime, backwards);
  filter_->AddStrain(deflection, estimate);
  InputStatusFacts input;
  if (!IsFinite(*estimate)) {
    ReplaceNonFinite(sample, estimate);
    input.non_finite_replaced = true;
  } else {
    last_finite_estimate_ = *estimate;
    has_finite_estimate_ = true;
  }
  FillInputFacts(sample.utime, stale, &input);
  const ConsistencyStatusFacts consistency = JudgeConsistency(deflection, *estimate);  // MODEL_MISMATCH withdraws VALID
  WidenForOffsetDeparture(consistency, estimate);
  if (consistency.tip_mass_unconfirmed) WidenForUnconfirmedTipMass(estimate);
  HandOverTipMass();
  const MultiArmStatusBits bits = ComposeMultiArmForceStatus(filter_->facts(), input, consistency,
                                                             TransportStatusFacts(), config_.vehicle.arm_count);
  health_.last_filter_facts = filter_->facts();
  health_.last_input_facts = input;
  health_.last_consistency_facts = consistency;
  estimate->status = bits.status;
  estimate->rotor_fault_bits = bits.rotor_fault_bits;
  ++health_.published;
  health_.last_status = bits.status;
  health_.last_rotor_fault_bits = bits.rotor_fault_bits;
  health_.last_estimate = *estimate;
  return true;
}

MultiArmStrainSample MultiArmPipeline::Condition(const MultiArmStrainSample& sample, int64_t previous_utime,
                                                 bool backwards_jump) {
  MultiArmStrainSample deflection = sample;
  for (int i = 0; i < config_.vehicle.arm_count && offsets_resumed_; ++i) {
    // The method reads gauge i with the description's o_i: the reading it
    // gets is moved by that minus the offset in use (a NaN stays NaN).
    const size_t k = static_cast<size_t>(i);
    deflection.deflection_rad[k] += config_.vehicle.arms[k].gauge_offset_rad - calibration_.offset_rad[k];
  }
  if (!notch_on_) return deflection;
  rotor_speed_.Advance(sample.utime);
  std::array<double, kMaxArms> omega_rad_s{};
  for (int i = 0; i < config_.vehicle.arm_count; ++i) omega_rad_s[static_cast<size_t>(i)] = rotor_speed_.omega_rad_s(i);
  const double dt_s =
      previous_utime >= 0 && !backwards_jump ? 1e-6 * static_cast<double>(sample.utime - previous_utime) : 0.0;
  notch_.Apply(dt_s, omega_rad_s, &deflection);
  return deflection;
}

bool MultiArmPipeline::OffsetsInUse(ArmValues* offset_rad, ArmValues* offset_std_rad) const {
  bool learned = false;
  for (int i = 0; i < config_.vehicle.arm_count; ++i) {
    const size_t k = static_cast<size_t>(i);
    double learned_rad = 0, learned_std_rad = 0;  // e_i and its sigma, in deflection
    (*offset_rad)[k] = calibration_.offset_rad[k];
    (*offset_std_rad)[k] = calibration_.offset_std_rad[k];
    if (!filter_->LearnedGaugeOffset(i, &learned_rad, &learned_std_rad)) continue;
    const double scale = config_.vehicle.arms[k].gauge_scale;
    (*offset_rad)[k] += scale * learned_rad;
    (*offset_std_rad)[k] = scale * learned_std_rad;
    learned = true;
  }
  return learned;
}

ConsistencyStatusFacts MultiArmPipeline::JudgeConsistency(const MultiArmStrainSample& deflection,
                                                          const MultiArmForceEstimate& estimate) {
  const FusionReports* reports = filter_->reports();
  bool outlier = false;  // a spike the filter's gate rejected would ring the arm-mode test's band-pass
  if (reports != nullptr) {
    for (const FusionReport& report : *reports) {
      consistency_.Add(report);
      CountFusionReport(report, health_.inputs, &health_.accelerometer);
      outlier = outlier || (report.source == FusionSource::kStrain && report.outcome == FusionOutcome::kRejectedGate);
    }
  }
  consistency_.AddStrain(deflection.utime, deflection.deflection_rad.data(), !filter_->body_supported(), outlier);
  ArmValues offset_rad, offset_std_rad;
  if (OffsetsInUse(&offset_rad, &offset_std_rad))
    consistency_.AddOffsets(deflection.utime, offset_rad.data(), !filter_->body_supported(),
                            filter_->body_near_ground());
  for (int i = 0; i < config_.vehicle.arm_count; ++i) {
    health_.strain_noise_scale[static_cast<size_t>(i)] = filter_->strain_noise_scale(i);
  }
  consistency_.SetStrainNoiseScales(health_.strain_noise_scale.data());
  const ConsistencyStatusFacts facts = consistency_.Judge(estimate.utime, estimate.thrust_scale.data());
  health_.consistency = consistency_.state();
  return facts;
}

void MultiArmPipeline::HandOverTipMass() {
  const ArmModeState& arm_mode = health_.consistency.arm_mode;
  if (!arm_mode.learning) return;
  if (arm_mode.tip_mass_readings > 0) health_.tip_mass_from_state_file = false;  // refined in this run
  health_.tip_mass_learned = true;
  health_.tip_mass_ratio = arm_mode.tip_mass_ratio;
  health_.tip_mass_ratio_std = arm_mode.tip_mass_ratio_std;
  if (arm_mode.tip_mass_ratio == tip_mass_ratio_in_filter_) return;
  filter_->SetTipMassScale(arm_mode.tip_mass_ratio);
  tip_mass_ratio_in_filter_ = arm_mode.tip_mass_ratio;
}

bool MultiArmPipeline::CheckStrainTiming(int64_t utime, int64_t previous_utime, bool backwards_jump) {
  if (!started_) {
    ResetFilter(ResetReason::kStart, utime);
    started_ = true;
    return false;
  }
  if (backwards_jump) {
    ResetFilter(ResetReason::kTimeBackwards, utime);
    return false;
  }
  const double interval_s = 1e-6 * static_cast<double>(utime - previous_utime);
  if (interval_s > config_.pipeline.reset_gap_s) {
    ResetFilter(ResetReason::kGap, utime);
    return false;
  }
  return interval_s > config_.pipeline.strain_timeout_s;
}

void MultiArmPipeline::ResetFilter(ResetReason reason, int64_t utime) {
  filter_->Reset();
  consistency_.Restart();
  ++health_.resets;
  health_.last_reset_reason = reason;
  reset_flag_pending_ = true;
  // The newest command still holds (within the motor timeout): the filter
  // starts from it, without its telemetry (already fused before the reset).
  if (has_motor_ && 1e-6 * static_cast<double>(utime - last_motor_.utime) <= config_.pipeline.motor_timeout_s) {
    MultiArmMotorSample command = last_motor_;
    command.omega_meas_rad_s.fill(std::numeric_limits<double>::quiet_NaN());
    filter_->AddMotor(command);
  }
}

void MultiArmPipeline::ReplaceNonFinite(const MultiArmStrainSample& sample, MultiArmForceEstimate* estimate) {
  ResetFilter(ResetReason::kNumerical, sample.utime);
  if (has_finite_estimate_) {
    *estimate = last_finite_estimate_;
  } else {
    const HoverSolution hover = SolveHover(config_.vehicle);
    estimate->n_rotors = config_.vehicle.arm_count;
    for (int i = 0; i < estimate->n_rotors; ++i) {
      const size_t k = static_cast<size_t>(i);
      estimate->force_n[k] = hover.thrust_n[k];
      estimate->force_std_n[k] = hover.thrust_n[k];
      estimate->thrust_scale[k] = 1.0;
    }
  }
  estimate->utime = sample.utime;
  estimate->seq = sample.seq;
}

void MultiArmPipeline::WidenForOffsetDeparture(const ConsistencyStatusFacts& consistency,
                                               MultiArmForceEstimate* estimate) {
  for (int i = 0; i < estimate->n_rotors; ++i) {
    const size_t k = static_cast<size_t>(i);
    const double offsets_n = consistency.offset_force_std_n[k];
    if (offsets_n > 0) estimate->force_std_n[k] = std::hypot(estimate->force_std_n[k], offsets_n);
  }
}

void MultiArmPipeline::WidenForUnconfirmedTipMass(MultiArmForceEstimate* estimate) const {
  const double relative_std = health_.consistency.arm_mode.force_tip_mass_std;
  for (int i = 0; i < estimate->n_rotors; ++i) {
    const size_t k = static_cast<size_t>(i);
    estimate->force_std_n[k] = std::hypot(estimate->force_std_n[k], relative_std * arm_mode_.rotor_tip_weight_n[k]);
  }
}

void MultiArmPipeline::FillInputFacts(int64_t utime, bool stale, InputStatusFacts* facts) {
  if (!has_motor_ || first_motor_utime_ > utime) {
    facts->no_motor_input = true;
  } else if (1e-6 * static_cast<double>(utime - last_motor_.utime) > config_.pipeline.motor_timeout_s) {
    stale = true;
  }
  facts->stale = stale;
  facts->conflict = InputAdmission::AnyConflictActive(health_.inputs);
  facts->filter_reset = reset_flag_pending_;
  reset_flag_pending_ = false;
}

void MultiArmPipeline::TakePeriod() {
  for (InputCounters& c : health_.inputs) ClearPeriod(&c);
  ClearPeriod(&health_.accelerometer);
}

}  // namespace birotor
