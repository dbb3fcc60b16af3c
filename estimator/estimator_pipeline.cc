#include "estimator/estimator_pipeline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "samples/rotor_count.h"

namespace birotor {
namespace {

bool FiniteWithin(double value, double limit) { return std::isfinite(value) && std::abs(value) <= limit; }

bool IsFinite(const ForceEstimate& e) {
  for (int i = 0; i < kBirotorRotors; ++i) {
    if (!std::isfinite(e.force_n[i]) || !std::isfinite(e.force_std_n[i]) || !std::isfinite(e.thrust_scale[i])) {
      return false;
    }
  }
  return true;
}

InputCounters& Counters(PipelineHealth* health, InputChannel channel) {
  return health->inputs[static_cast<int>(channel)];
}

// The model's mode over m_p when the arm-mode test learns the tip mass
// (switched on, and a method that flies it).
ArmModeTipMassMap TipMassMapOf(const ModelConsistencyOptions& options, const BirotorParams& params,
                               const ForceEstimator& method) {
  const bool learns =
      options.enabled && options.arm_mode_enabled && options.arm_mode_learn_tip_mass && method.flies_tip_mass();
  return learns ? ArmModeTipMassMap::Of(params) : ArmModeTipMassMap();
}

// The priors and limits of what learned strain scales are
// (estimator/strain_scale_attribution.h), from the configuration and the
// model's mode over the tip mass.
ScaleAttributionOptions ScaleAttributionOptionsOf(const EstimatorConfig& config, const ArmModeTipMassMap& tip_mass) {
  const ModelConsistencyOptions& mc = config.model_consistency;
  ScaleAttributionOptions o;
  o.stiffness_prior_std = mc.scale_attribution_stiffness_std;
  o.gauge_scale_prior_std = mc.scale_attribution_gauge_scale_std;
  o.tip_mass_prior_std = mc.arm_mode_unconfirmed_tip_mass_std;
  o.common_scale_prior_std = config.ekf.body_mass_scale_prior_std;
  o.change_probability = mc.arm_mode_tip_mass_change_probability;
  o.tolerance = mc.scale_attribution_tolerance;
  o.explained_distance2 = mc.scale_attribution_limit;
  if (!tip_mass.empty()) o.tip_mass_mode_slope = tip_mass.LogHzSlope(1.0);
  return o;
}

double GateOf(const ForceEstimator& method, InputChannel channel) {
  FusionSource source;
  return GatedSourceOf(channel, &source) ? method.Gate(source) : std::numeric_limits<double>::quiet_NaN();
}

EstimationMethod MethodOrThrow(const std::string& name) {
  EstimationMethod method;
  if (!ParseEstimationMethod(name, &method)) throw std::invalid_argument("unknown estimation method '" + name + "'");
  return method;
}

}  // namespace

const char* ResetReasonName(ResetReason reason) {
  switch (reason) {
    case ResetReason::kNone:
      return "";
    case ResetReason::kStart:
      return "start";
    case ResetReason::kGap:
      return "gap";
    case ResetReason::kTimeBackwards:
      return "time_backwards";
    case ResetReason::kNumerical:
      return "numerical";
  }
  return "?";
}

double GateOf(const EstimatorConfig& config, InputChannel channel) {
  const std::unique_ptr<ForceEstimator> method = MakeForceEstimator(config);
  return method ? GateOf(*method, channel) : std::numeric_limits<double>::quiet_NaN();
}

EstimatorPipeline::EstimatorPipeline(const EstimatorConfig& config)
    : config_(config),
      model_(BirotorModelOf(config.vehicle)),
      method_kind_(MethodOrThrow(config.method)),
      method_(MakeForceEstimator(method_kind_, config)),
      admission_(config.pipeline),
      tare_(model_, config.tare),
      rotor_speed_(model_, config.pipeline.motor_timeout_s),
      notch_(config.harmonic_notch),
      tip_mass_map_(TipMassMapOf(config.model_consistency, model_, *method_)),
      attributes_scales_(config.ekf.learn_strain_scale && !tip_mass_map_.empty()),
      scale_attribution_options_(ScaleAttributionOptionsOf(config, tip_mass_map_)),
      consistency_(config.model_consistency, ExpectedArmMode(model_), config.ekf.strain_noise_rad, kBirotorRotors,
                   tip_mass_map_) {
  calibration_ = GaugeCalibration::FromVehicle(model_);
  health_.gauge = calibration_;
  double direction[kBirotorRotors], drift_psd_rad2_s[kBirotorRotors], force_per_direction_n[kBirotorRotors];
  for (int i = 0; i < kBirotorRotors; ++i) {
    // The raw reading s_i b_i moves by s_i kArmSign_i L / k per newton of
    // rotor i, and a payload adds the same newtons to both rotors: one
    // direction (a radian of b_i) is k / L newtons.
    direction[i] = kArmSign[i] * calibration_.scale[i];
    drift_psd_rad2_s[i] = model_.gauge_drift_psd_rad2_s;
    force_per_direction_n[i] = model_.arm_stiffness_n_m_rad / model_.arm_length_m;
  }
  // With learned strain scales a common force goes to the scales as much as
  // to the offsets (split again after each settling): the test is run only
  // when the arm mode tells the scales apart, and a departure is released
  // while they stand for the forces (ModelConsistencyMonitor::AddScaleAttribution).
  if (!config.ekf.learn_strain_scale || attributes_scales_)
    consistency_.SetOffsetGauges(direction, drift_psd_rad2_s, force_per_direction_n);
  consistency_.AnchorOffsets(calibration_.offset_rad, calibration_.offset_std_rad);
  health_.body_mass_kg = config.vehicle.body_mass_kg;
  health_.tip_mass_kg = model_.tip_mass_kg;
  health_.strain_noise_learned = method_->learns_strain_noise();
  for (int i = 0; i < kNumInputChannels; ++i) health_.inputs[i].gate = GateOf(*method_, static_cast<InputChannel>(i));
  health_.accelerometer.gate = method_->Gate(FusionSource::kAccelerometer);
}

EstimatorPipeline::~EstimatorPipeline() = default;

void EstimatorPipeline::CountReceived(InputChannel channel) { ++Counters(&health_, channel).received; }
void EstimatorPipeline::CountDecodeError(InputChannel channel) { ++Counters(&health_, channel).decode_errors; }
void EstimatorPipeline::CountOverloadDrop(InputChannel channel) { ++Counters(&health_, channel).dropped_overload; }

void EstimatorPipeline::SetGaugeOffsets(const GaugeCalibration& calibration) {
  UseGaugeOffsets(calibration.offset_rad, calibration.offset_std_rad, calibration.source);
  consistency_.AnchorOffsets(calibration.offset_rad, calibration.offset_std_rad);
  if (calibration.has_tip_mass) ResumeTipMass(calibration.tip_mass_kg, calibration.tip_mass_std_kg);
  if (!calibration.has_strain_scale) return;
  // Learned in an earlier run: the method starts from it (if it learns it).
  health_.strain_scale_from_state_file = true;
  LearnedVehicleParameters learned;
  learned.has_strain_scale = true;
  for (int i = 0; i < kBirotorRotors; ++i) {
    learned.strain_scale[i] = calibration.strain_scale[i];
    learned.strain_scale_std[i] = calibration.strain_scale_std[i];
  }
  method_->SetLearnedParameters(learned);
}

void EstimatorPipeline::UseGaugeOffsets(const double offset_rad[kBirotorRotors],
                                        const double offset_std_rad[kBirotorRotors], GaugeOffsetSource source) {
  double prior_std_rad[2];  // in deflection: o_i / s_i
  for (int i = 0; i < kBirotorRotors; ++i) {
    calibration_.offset_rad[i] = offset_rad[i];
    calibration_.offset_std_rad[i] = offset_std_rad[i];
    prior_std_rad[i] = offset_std_rad[i] / calibration_.scale[i];
  }
  calibration_.source = source;
  health_.gauge = calibration_;
  method_->SetGaugeOffsetPrior(prior_std_rad);
}

void EstimatorPipeline::AnchorOffsetsAtTare() {
  // The tare subtracts the file's rest reading s_i b_rest_i = -s_i kArmSign_i
  // L m_p g / k; a tip mass other than the file's (its prior's relative sigma)
  // moves the offsets the flight needs by that share of it.
  const double tip_mass_share = config_.model_consistency.arm_mode_unconfirmed_tip_mass_std;
  double std_rad[kBirotorRotors];
  for (int i = 0; i < kBirotorRotors; ++i)
    std_rad[i] = std::hypot(tare_.offset_std_rad()[i], tip_mass_share * RestReadingRad(model_, i));
  consistency_.AnchorOffsets(tare_.offset_rad(), std_rad);
}

void EstimatorPipeline::UpdateReportedGaugeOffsets(const StrainStepInfo& info) {
  // o_i in use = calibration + s_i e_i, one sigma s_i std(e_i).
  // The learned strain scale g_i and its sigma, as learned (persisted with the offsets).
  health_.gauge.has_strain_scale = info.has_learned_strain_scale;
  for (int i = 0; i < 2 && info.has_learned_strain_scale; ++i) {
    health_.gauge.strain_scale[i] = info.learned_strain_scale[i];
    health_.gauge.strain_scale_std[i] = info.learned_strain_scale_std[i];
  }
  if (info.has_learned_strain_scale && !attributes_scales_)
    consistency_.SetLearnedStrainScales(info.learned_strain_scale, info.learned_strain_scale_std);
  consistency_.SetStrainNoiseScales(info.strain_noise_scale);
  for (int i = 0; i < 2; ++i) health_.strain_noise_scale[i] = info.strain_noise_scale[i];
  health_.body_mass_learned = info.has_learned_body_mass;
  if (info.has_learned_body_mass) {
    health_.body_mass_kg = info.learned_body_mass_kg;
    health_.body_mass_std_kg = info.learned_body_mass_std_kg;
  }
  if (!info.has_learned_gauge_offset) return;
  for (int i = 0; i < kBirotorRotors; ++i) {
    health_.gauge.offset_rad[i] = calibration_.offset_rad[i] + calibration_.scale[i] * info.learned_gauge_offset_rad[i];
    health_.gauge.offset_std_rad[i] = calibration_.scale[i] * info.learned_gauge_offset_std_rad[i];
  }
}

void EstimatorPipeline::TakePeriod() {
  for (InputCounters& c : health_.inputs) ClearPeriod(&c);
  ClearPeriod(&health_.accelerometer);
}

void EstimatorPipeline::CountReports() {
  for (const FusionReport& report : reports_) Count(report);
}

void EstimatorPipeline::Count(const FusionReport& report) {
  consistency_.Add(report);
  CountFusionReport(report, health_.inputs, &health_.accelerometer);
}

bool EstimatorPipeline::Admit(InputChannel channel, int64_t utime, int32_t seq, Admission* admission) {
  *admission = admission_.Admit(channel, utime, seq, health_.inputs);
  health_.newest_utime = admission_.newest_utime();
  return IsAccepted(*admission);
}

void EstimatorPipeline::ResetMethod(ResetReason reason, int64_t utime) {
  ++health_.resets;
  health_.last_reset_reason = reason;
  reset_flag_pending_ = true;
  consistency_.Restart();
  if (reason == ResetReason::kStart) return;  // the method is new: it keeps what it was given so far
  // What the method learned about the gauge offsets survives the reset.
  const GaugeCalibration learned = health_.gauge;
  reports_.clear();
  method_->Reset(&reports_);
  CountReports();
  UseGaugeOffsets(learned.offset_rad, learned.offset_std_rad, learned.source);
  if (has_motor_ && last_motor_.utime <= utime &&
      (utime - last_motor_.utime) * 1e-6 <= config_.pipeline.motor_timeout_s) {
    // The command only: its telemetry was already given to (and reported by) the method.
    MotorSample command = last_motor_;
    command.omega_meas_rad_s[0] = command.omega_meas_rad_s[1] = std::numeric_limits<double>::quiet_NaN();
    reports_.clear();
    method_->AddMotor(command, &reports_);
    CountReports();
  }
}

void EstimatorPipeline::OnMotor(const MotorSample& sample) {
  InputCounters& c = Counters(&health_, InputChannel::kMotor);
  const double limit = config_.pipeline.max_omega_rad_s;
  bool valid = FiniteWithin(sample.omega_cmd_rad_s[0], limit) && FiniteWithin(sample.omega_cmd_rad_s[1], limit);
  for (double meas : sample.omega_meas_rad_s) valid = valid && (std::isnan(meas) || FiniteWithin(meas, limit));
  if (!valid) {
    ++c.rejected_invalid;
    return;
  }
  Admission admission;
  if (!Admit(InputChannel::kMotor, sample.utime, sample.seq, &admission)) return;
  if (std::isnan(sample.omega_meas_rad_s[0]) || std::isnan(sample.omega_meas_rad_s[1])) ++c.reading_missing;
  if (!has_motor_) first_motor_utime_ = sample.utime;
  last_motor_ = sample;
  has_motor_ = true;
  tare_.AddMotor(sample);
  rotor_speed_.AddMotor(sample);
  reports_.clear();
  method_->AddMotor(sample, &reports_);  // fused / rejected / not fused: counted from its reports
  CountReports();
}

void EstimatorPipeline::OnImu(const ImuSample& sample) {
  InputCounters& c = Counters(&health_, InputChannel::kImu);
  if (!FiniteWithin(sample.gyro_y_rad_s, config_.pipeline.max_gyro_rad_s)) {
    ++c.rejected_invalid;
    return;
  }
  Admission admission;
  if (!Admit(InputChannel::kImu, sample.utime, sample.seq, &admission)) return;
  // The accelerometer feeds the tare and the ground contact, which both skip
  // a NaN there (a missing reading); the gyro still counts.
  if (!std::isfinite(sample.accel_x_m_s2) || !std::isfinite(sample.accel_z_m_s2)) ++c.reading_missing;
  if (std::isfinite(sample.accel_z_m_s2)) CountAccelerometerSample(sample.utime, sample.seq, &health_.accelerometer);
  tare_.AddImu(sample);
  reports_.clear();
  method_->AddImu(sample, &reports_);
  CountReports();
}

void EstimatorPipeline::OnPose(const PoseSample& sample) {
  InputCounters& c = Counters(&health_, InputChannel::kPose);
  if (!std::isfinite(sample.x_m) || !std::isfinite(sample.z_m) || !std::isfinite(sample.phi_rad)) {
    ++c.rejected_invalid;
    return;
  }
  // Counted for the health; the method may take the height (its ground contact).
  Admission admission;
  if (Admit(InputChannel::kPose, sample.utime, sample.seq, &admission)) method_->AddPose(sample);
}

bool EstimatorPipeline::OnStrain(const StrainSample& sample, ForceEstimate* estimate) {
  InputCounters& c = Counters(&health_, InputChannel::kStrain);
  const double limit = config_.pipeline.max_deflection_rad;
  if (!FiniteWithin(sample.deflection_rad[0], limit) || !FiniteWithin(sample.deflection_rad[1], limit)) {
    ++c.rejected_invalid;
    return false;
  }
  const int64_t previous_utime = c.last_utime;
  Admission admission;
  if (!Admit(InputChannel::kStrain, sample.utime, sample.seq, &admission)) return false;
  const bool backwards = admission == Admission::kAcceptedBackwardsJump;

  const bool stale = CheckStrainTiming(sample, previous_utime, backwards);
  const StrainSample deflection = Condition(sample, previous_utime, backwards);
  StrainStepInfo info;
  reports_.clear();
  method_->AddStrain(deflection, estimate, &info, &reports_);
  CountReports();
  bool outlier = false;  // a spike the method's gate rejected would ring the arm-mode test's band-pass
  for (const FusionReport& report : reports_) {
    outlier = outlier || (report.source == FusionSource::kStrain && report.outcome == FusionOutcome::kRejectedGate);
  }
  consistency_.AddStrain(deflection.utime, deflection.deflection_rad, !info.body_supported, outlier);
  HandOverTipMass();
  UpdateReportedGaugeOffsets(info);
  if (attributes_scales_ && health_.gauge.has_strain_scale) JudgeLearnedScales(deflection.utime);
  if (info.has_learned_gauge_offset)
    consistency_.AddOffsets(deflection.utime, health_.gauge.offset_rad, !info.body_supported);
  if (info.reset != ResetReason::kNone) {
    // The method re-initialised itself (its numerical guard).
    ++health_.resets;
    health_.last_reset_reason = info.reset;
    reset_flag_pending_ = true;
  }
  ForceStatusFacts facts;
  facts.filter = info.filter;
  if (!IsFinite(*estimate)) {
    ReplaceNonFinite(sample, estimate);
    facts.input.non_finite_replaced = true;  // forces and sigmas of the last finite estimate
  } else {
    last_finite_estimate_ = *estimate;
    has_finite_estimate_ = true;
  }
  FillInputFacts(sample, stale, &facts.input);
  facts.consistency = consistency_.Judge(*estimate);  // MODEL_MISMATCH withdraws VALID (docs/mismatch.md)
  Publish(facts, estimate);
  return true;
}

void EstimatorPipeline::ResumeTipMass(double tip_mass_kg, double std_kg) {
  // With arm_mode_learn_tip_mass off the file's m_p is flown, as a persisted
  // strain scale is not flown with learn_strain_scale off, and the next stop
  // does not write it back. (With learn_strain_scale the persisted m_p is
  // the attributed one, HandOverTipMass.)
  if (!consistency_.ResumeTipMass(tip_mass_kg, std_kg)) return;
  const ArmModeState& arm_mode = consistency_.state().arm_mode;
  health_.tip_mass_learned = true;
  health_.tip_mass_from_state_file = true;
  health_.tip_mass_kg = arm_mode.tip_mass_kg;
  health_.tip_mass_std_kg = arm_mode.tip_mass_std_kg;
  method_->SetTipMassKg(arm_mode.tip_mass_kg);  // flown from the first sample (a reset keeps it)
  tip_mass_in_method_kg_ = arm_mode.tip_mass_kg;
}

void EstimatorPipeline::HandOverTipMass() {
  const ArmModeState& arm_mode = consistency_.state().arm_mode;
  if (!arm_mode.learning) return;
  if (arm_mode.tip_mass_readings > 0) health_.tip_mass_from_state_file = false;  // refined in this run
  // With learned strain scales the mode's shift may be a stiffness's
  // (JudgeLearnedScales): by that weight, and a payload's, the tip mass is
  // the file's. What is flown is what is reported and persisted.
  const double flown =
      arm_mode.tip_mass_kg + tip_mass_file_share_ * (tip_mass_map_.file_tip_mass_kg() - arm_mode.tip_mass_kg);
  health_.tip_mass_learned = true;
  health_.tip_mass_kg = flown;
  health_.tip_mass_std_kg = arm_mode.tip_mass_std_kg;
  if (flown == tip_mass_in_method_kg_) return;
  method_->SetTipMassKg(flown);
  tip_mass_in_method_kg_ = flown;
}

void EstimatorPipeline::JudgeLearnedScales(int64_t utime) {
  // Every 20 ms: the scales and the mode move over seconds.
  const int64_t since_us = utime - scales_judged_utime_;
  if (scales_judged_utime_ >= 0 && since_us >= 0 && since_us < kScaleJudgementIntervalUs) return;
  scales_judged_utime_ = utime;
  const ScaleAttribution a = AttributeLearnedScales();
  tip_mass_file_share_ = a.of(ScaleChange::kStiffness) + a.of(ScaleChange::kCommonScale);
  consistency_.AddScaleAttribution(utime, a);
}

ScaleAttribution EstimatorPipeline::AttributeLearnedScales() const {
  const ArmModeState& arm_mode = consistency_.state().arm_mode;
  ScaleEvidence e;
  for (int i = 0; i < 2; ++i) {
    const double g = health_.gauge.strain_scale[i], g_std = health_.gauge.strain_scale_std[i];
    e.log_scale[i] = std::log(g);
    e.log_scale_var[i] = (g_std / g) * (g_std / g);
  }
  const double r = arm_mode.learned_ratio;
  e.mode_shift = tip_mass_map_.LogHz(r) - tip_mass_map_.LogHz(1.0);
  const double shift_std = tip_mass_map_.LogHzSlope(r) * arm_mode.learned_ratio_std;
  e.mode_shift_var = shift_std * shift_std;
  return AttributeScales(e, scale_attribution_options_);
}

void EstimatorPipeline::Publish(const ForceStatusFacts& facts, ForceEstimate* estimate) {
  // The offsets' departure and the unconfirmed tip mass's prior
  // (facts.consistency), as the facts say.
  for (int i = 0; i < kBirotorRotors; ++i)
    estimate->force_std_n[i] = PublishedForceStd(estimate->force_std_n[i], facts, i);
  estimate->status = ComposeForceStatus(facts);
  health_.consistency = consistency_.state();
  ++health_.published;
  health_.last_status = estimate->status;
  health_.last_status_facts = facts;
  health_.last_estimate = *estimate;
}

bool EstimatorPipeline::CheckStrainTiming(const StrainSample& sample, int64_t previous_utime, bool backwards_jump) {
  if (!started_) {
    ResetMethod(ResetReason::kStart, sample.utime);
    started_ = true;
    return false;
  }
  if (backwards_jump) {
    ResetMethod(ResetReason::kTimeBackwards, sample.utime);
    return false;
  }
  const double interval_s = (sample.utime - previous_utime) * 1e-6;
  if (interval_s > config_.pipeline.reset_gap_s) {
    ResetMethod(ResetReason::kGap, sample.utime);
    return false;
  }
  return interval_s > config_.pipeline.strain_timeout_s;
}

StrainSample EstimatorPipeline::Condition(const StrainSample& sample, int64_t previous_utime, bool backwards_jump) {
  if (tare_.AddStrain(sample) == TareEvent::kAccepted) {
    UseGaugeOffsets(tare_.offset_rad(), tare_.offset_std_rad(), GaugeOffsetSource::kTare);
    AnchorOffsetsAtTare();
  }
  health_.tare = tare_.counters();
  StrainSample deflection = calibration_.Apply(sample);
  if (config_.harmonic_notch.enabled) {
    rotor_speed_.Advance(sample.utime);
    const double omega_rad_s[kBirotorRotors] = {rotor_speed_.omega_rad_s(0), rotor_speed_.omega_rad_s(1)};
    const double dt_s = previous_utime >= 0 && !backwards_jump ? (sample.utime - previous_utime) * 1e-6 : 0.0;
    notch_.Apply(dt_s, omega_rad_s, &deflection);
  }
  return deflection;
}

void EstimatorPipeline::ReplaceNonFinite(const StrainSample& sample, ForceEstimate* estimate) {
  ResetMethod(ResetReason::kNumerical, sample.utime);
  if (has_finite_estimate_) {
    *estimate = last_finite_estimate_;
  } else {
    for (int i = 0; i < kBirotorRotors; ++i) {
      estimate->force_n[i] = model_.HoverForceN();
      estimate->force_std_n[i] = model_.HoverForceN();
      estimate->thrust_scale[i] = 1.0;
    }
  }
  estimate->utime = sample.utime;
  estimate->seq = sample.seq;
}

void EstimatorPipeline::FillInputFacts(const StrainSample& sample, bool stale, InputStatusFacts* facts) {
  if (!has_motor_ || first_motor_utime_ > sample.utime) {
    facts->no_motor_input = true;
  } else if ((sample.utime - last_motor_.utime) * 1e-6 > config_.pipeline.motor_timeout_s) {
    stale = true;
  }
  facts->stale = stale;
  facts->conflict = InputAdmission::AnyConflictActive(health_.inputs);
  facts->filter_reset = reset_flag_pending_;
  reset_flag_pending_ = false;
}

}  // namespace birotor
