// Windowed NIS, bias and whiteness of the fusion reports; the decision.
#include "estimator/model_consistency.h"

#include <algorithm>
#include <cmath>

#include "samples/rotor_count.h"

namespace birotor {

const char* MismatchParameterName(MismatchParameter parameter) {
  switch (parameter) {
    case MismatchParameter::kNone:
      return "";
    case MismatchParameter::kStiffnessOrGaugeScale:
      return "stiffness_or_gauge_scale";
    case MismatchParameter::kMass:
      return "mass";
    case MismatchParameter::kMotorLag:
      return "motor_lag";
    case MismatchParameter::kTipMass:
      return "tip_mass";
  }
  return "";
}

ModelConsistencyMonitor::ModelConsistencyMonitor(const ModelConsistencyOptions& options,
                                                 const ArmModeExpectation& arm_mode, double strain_noise_rad,
                                                 int rotors, const ArmModeTipMassMap& tip_mass)
    : options_(options),
      rotors_(std::clamp(rotors, 1, kMaxSampleArms)),
      arm_mode_file_(arm_mode),
      arm_mode_(options, arm_mode, strain_noise_rad, tip_mass),
      offsets_(0.0, 0.0, rotors, UnitThrustScales().data(), ArmValues{}.data()),
      window_us_(static_cast<int64_t>(std::llround(options.window_s * 1e6))) {
  state_.arm_mode = arm_mode_.state();
}

void ModelConsistencyMonitor::AddStrain(int64_t utime, const double* deflection_rad, bool airborne, bool outlier) {
  if (!options_.enabled || !judging_) return;
  const bool arm_mode_mismatch = arm_mode_.Add(utime, deflection_rad, airborne, outlier);
  state_.arm_mode = arm_mode_.state();
  if (arm_mode_mismatch && !state_.mismatch) {
    // The rigid body's tests see nothing of a tip-mass error: the name is
    // the arm mode's.
    state_.raised_fast = false;
    Raise(utime, newest_thrust_scale_.data());
    state_.parameter = MismatchParameter::kTipMass;
  } else if (!arm_mode_mismatch && state_.mismatch && state_.parameter == MismatchParameter::kTipMass &&
             consistent_run_ >= options_.clear_windows && !DepartureHolds() && !state_.scales_unexplained) {
    // Cleared by the arm-mode test, the windows as consistent as their own clearing needs.
    state_.mismatch = false;
  }
}

void ModelConsistencyMonitor::SetOffsetGauges(const double* direction, const double* drift_psd_rad2_s,
                                              const double* force_per_direction_n) {
  offsets_ = OffsetDepartureTest(options_.offset_departure_limit, options_.offset_departure_hold_s, rotors_, direction,
                                 drift_psd_rad2_s);
  for (int i = 0; i < rotors_ && i < kMaxSampleArms; ++i) {
    force_per_direction_n_[static_cast<size_t>(i)] =
        std::isfinite(force_per_direction_n[i]) ? std::fabs(force_per_direction_n[i]) : 0.0;
  }
  state_.offsets = offsets_.state();
}

void ModelConsistencyMonitor::AnchorOffsets(const double* offset_rad, const double* offset_std_rad) {
  offsets_.Anchor(offset_rad, offset_std_rad);
  state_.offsets = offsets_.state();
}

void ModelConsistencyMonitor::AddOffsets(int64_t utime, const double* offset_rad, bool free_flight, bool near_ground) {
  if (!options_.enabled || !judging_ || !offsets_.enabled()) return;
  const bool departed = offsets_.Add(utime, offset_rad, free_flight, near_ground);
  state_.offsets = offsets_.state();
  if (departed && !state_.mismatch) {
    // The filter's innovations are white: the name is the offsets' (along
    // the common force a payload, or every arm's stiffness or gauge scale
    // alike; one gauge alone: its arm's gauge or stiffness, or a support
    // holding the body near the ground).
    state_.raised_fast = false;
    Raise(utime, newest_thrust_scale_.data());
    state_.parameter =
        state_.offsets.departed_arm >= 0 ? MismatchParameter::kStiffnessOrGaugeScale : MismatchParameter::kMass;
  }
}

void ModelConsistencyMonitor::AddScaleAttribution(int64_t utime, const ScaleAttribution& attribution) {
  if (!options_.enabled || !judging_) return;
  const double payload = attribution.of(ScaleChange::kCommonScale);
  const double changed = attribution.of(ScaleChange::kStiffness) + attribution.of(ScaleChange::kTipMass) +
                         attribution.of(ScaleChange::kGauge1) + attribution.of(ScaleChange::kGauge2);
  const double stand = options_.scale_attribution_stand_weight;
  scales_stand_ = attribution.explained && 1.0 - payload >= stand;
  if (state_.scales_unexplained) {
    // Raised: held until a stiffness, a gauge's scale or a tip mass explains the scales.
    if (attribution.explained && changed >= stand) {
      state_.scales_unexplained = false;
      scales_suspect_since_ = -1;
    }
    return;
  }
  if (attribution.explained && payload <= options_.scale_attribution_payload_weight) {
    scales_suspect_since_ = -1;
    return;
  }
  if (scales_suspect_since_ < 0) scales_suspect_since_ = utime;
  if (utime - scales_suspect_since_ < static_cast<int64_t>(options_.offset_departure_hold_s * 1e6)) return;
  state_.scales_unexplained = true;
  if (!state_.mismatch) {
    state_.raised_fast = false;
    Raise(utime, newest_thrust_scale_.data());
    state_.parameter = attribution.explained ? MismatchParameter::kMass : MismatchParameter::kStiffnessOrGaugeScale;
  }
}

void ModelConsistencyMonitor::Restart() {
  arm_mode_.Restart();
  state_.arm_mode = arm_mode_.state();
  window_start_utime_ = -1;
  for (Accumulator& a : acc_) a = Accumulator();
  cusum_high_ = cusum_low_ = 0;
  thrust_scale_sum_.fill(0.0);
  estimates_ = 0;
}

void ModelConsistencyMonitor::Advance(int64_t utime) {
  if (window_start_utime_ < 0) window_start_utime_ = utime;
  if (utime - window_start_utime_ >= window_us_) CloseWindow(utime);
}

ConsistencyStatusFacts ModelConsistencyMonitor::Judge(int64_t utime, const double* thrust_scale) {
  ConsistencyStatusFacts facts;
  // A method without innovations (the baselines) is not judged.
  if (!options_.enabled || !judging_) return facts;
  Advance(utime);
  for (int i = 0; i < rotors_; ++i) {
    const size_t k = static_cast<size_t>(i);
    thrust_scale_sum_[k] += thrust_scale[i];
    newest_thrust_scale_[k] = thrust_scale[i];
  }
  ++estimates_;
  facts.mismatch = state_.mismatch;
  // Not yet checked: no deficit a mismatch may explain, and VALID only
  // where the controller must not wait for the check (option).
  facts.model_unconfirmed = !state_.mismatch && !state_.confirmed;
  facts.unconfirmed_withholds_valid = options_.valid_needs_confirmation;
  // Never set while the test is off.
  if (state_.arm_mode.awaiting_reading || state_.arm_mode.force_tip_mass_std > 0) AwaitArmMode(&facts);
  if (options_.offset_departure_in_sigma_above >= 0 && state_.offsets.statistic > 0 && !scales_stand_)
    CarryOffsetDeparture(&facts);
  return facts;
}

void ModelConsistencyMonitor::CarryOffsetDeparture(ConsistencyStatusFacts* facts) const {
  // The offsets moved by c times the common-force direction since their
  // anchor, z sigmas of their prior and drift: a payload would make c times
  // force_per_direction_n_ on each rotor; the share beyond z0 sigmas of it
  // is what the published sigma carries.
  const double z = std::fabs(state_.offsets.z);
  const double beyond =
      z > options_.offset_departure_in_sigma_above ? (z - options_.offset_departure_in_sigma_above) / z : 0.0;
  const double multiple = beyond * std::fabs(state_.offsets.common_multiple);
  for (int i = 0; i < rotors_ && i < kMaxSampleArms; ++i) {
    const size_t k = static_cast<size_t>(i);
    facts->offset_force_std_n[k] = multiple * force_per_direction_n_[k];
  }
}

void ModelConsistencyMonitor::AwaitArmMode(ConsistencyStatusFacts* facts) const {
  facts->tip_mass_unconfirmed = true;
  facts->tip_mass_withholds_valid = options_.arm_mode_valid_needs_reading && state_.arm_mode.awaiting_reading;
  // The tip mass unconfirmed (its prior) or learned (its sigma) in each
  // force's sigma: d f_i / d m_p = g at hover (docs/mismatch.md).
  facts->tip_mass_force_std_n = state_.arm_mode.force_tip_mass_std * arm_mode_file_.tip_weight_n;
}

void ModelConsistencyMonitor::Add(const FusionReport& report) {
  if (!options_.enabled || report.size <= 0 || !std::isfinite(report.nis)) return;
  judging_ = true;
  Advance(report.utime);
  AddToCusum(report);
  Accumulator& a = acc_[static_cast<int>(report.source)];
  ++a.reports;
  if (report.outcome == FusionOutcome::kRejectedGate) ++a.rejected;
  // Gated outliers (spikes) are input faults, judged by their share only.
  if (report.outcome != FusionOutcome::kFused) return;
  int measured = 0;
  for (int j = 0; j < std::min(report.size, kMaxMeasurementSize); ++j) {
    const double s = report.innovation_variance(j);
    if (!(s > 0)) continue;  // not measured: y_j = 0 and no share of the NIS
    const double z = report.innovation(j) / std::sqrt(s);
    a.z_sum[j] += z;
    a.z2_sum[j] += z * z;
    if (a.z_count[j] > 0) a.zz_lag_sum[j] += z * a.z_previous[j];
    a.z_previous[j] = z;
    ++a.z_count[j];
    ++measured;
  }
  if (measured == 0) return;
  a.nis_ratio_sum += report.nis / measured;
  ++a.count;
}

void ModelConsistencyMonitor::AddToCusum(const FusionReport& report) {
  const double s = report.innovation_variance(0);
  if (report.source != FusionSource::kAccelerometer || !(s > 0)) return;
  const ModelConsistencyOptions& o = options_;
  const double z = std::clamp(report.innovation(0) / std::sqrt(s), -o.fast_cusum_clip, o.fast_cusum_clip);
  cusum_high_ = std::max(0.0, cusum_high_ + z - o.fast_cusum_drift);
  cusum_low_ = std::max(0.0, cusum_low_ - z - o.fast_cusum_drift);
  const double cusum = std::max(cusum_high_, cusum_low_);
  state_.fast_cusum_peak = std::max(state_.fast_cusum_peak, cusum);
  state_.fast_statistic = o.fast_cusum_limit > 0 ? cusum / o.fast_cusum_limit : 0.0;
  if (state_.fast_statistic > 1.0 && !state_.mismatch) {
    state_.worst_source = report.source;
    state_.raised_fast = true;
    Raise(report.utime, newest_thrust_scale_.data());
    cusum_high_ = cusum_low_ = 0;  // fresh evidence for a raise after a clear
  }
}

void ModelConsistencyMonitor::Raise(int64_t utime, const double* thrust_scale) {
  state_.mismatch = true;
  state_.confirmed = false;
  state_.raised_utime = utime;
  ++state_.raised_count;
  state_.parameter = Attribute(thrust_scale);
}

void ModelConsistencyMonitor::CloseWindow(int64_t utime) {
  double statistic = 0;
  FusionSource worst = FusionSource::kStrain;
  for (int k = 0; k < kNumFusionSources; ++k) {
    Accumulator& a = acc_[k];
    SourceWindowStats& s = state_.last[k];
    s = SourceWindowStats();
    s.count = a.count;
    s.reports = a.reports;
    s.rejected = a.rejected;
    if (a.count > 0) s.nis_ratio = a.nis_ratio_sum / static_cast<double>(a.count);
    for (int j = 0; j < kMaxMeasurementSize; ++j) {
      if (a.z_count[j] == 0) continue;
      const double n = static_cast<double>(a.z_count[j]);
      s.bias[j] = a.z_sum[j] / n;
      const double variance = a.z2_sum[j] / n - s.bias[j] * s.bias[j];
      s.lag1[j] =
          variance > 0 && a.z_count[j] > 1 ? (a.zz_lag_sum[j] / (n - 1) - s.bias[j] * s.bias[j]) / variance : 0.0;
    }
    if (a.reports >= options_.min_reports) {
      double score = static_cast<double>(a.rejected) / a.reports / options_.rejected_share_limit;
      if (a.count >= options_.min_reports) score = std::max(score, s.nis_ratio / options_.nis_ratio_limit[k]);
      for (int j = 0; j < kMaxMeasurementSize; ++j)
        score = std::max(score, std::fabs(s.bias[j]) / options_.bias_limit[k]);
      if (score > statistic) {
        statistic = score;
        worst = static_cast<FusionSource>(k);
      }
    }
    a = Accumulator();
  }
  window_start_utime_ = utime;
  for (int i = 0; i < rotors_; ++i) {
    const size_t k = static_cast<size_t>(i);
    state_.thrust_scale_mean[k] = estimates_ > 0 ? thrust_scale_sum_[k] / estimates_ : 1.0;
    thrust_scale_sum_[k] = 0;
  }
  estimates_ = 0;
  ++state_.windows;
  state_.statistic = statistic;
  state_.worst_source = worst;
  if (statistic > 1.0) {
    consistent_run_ = 0;
    ++inconsistent_run_;
    if (inconsistent_run_ >= options_.raise_windows && !state_.mismatch) {
      state_.raised_fast = false;
      Raise(utime, state_.thrust_scale_mean.data());
    } else if (inconsistent_run_ == options_.raise_windows && state_.raised_fast) {
      // Raised by the fast test: the name is revised on the windows' evidence
      // (a thrust scale moves away from 1 in the first tens of ms only).
      state_.parameter = Attribute(state_.thrust_scale_mean.data());
    }
  } else {
    inconsistent_run_ = 0;
    ++consistent_run_;
    if (state_.mismatch && consistent_run_ >= options_.clear_windows && !arm_mode_.state().mismatch &&
        !DepartureHolds() && !state_.scales_unexplained) {
      state_.mismatch = false;
    }
  }
  state_.confirmed = !state_.mismatch && consistent_run_ >= options_.confirm_windows;
}

MismatchParameter ModelConsistencyMonitor::Attribute(const double* thrust_scale) const {
  switch (state_.worst_source) {
    case FusionSource::kTelemetry:
      return MismatchParameter::kMotorLag;
    case FusionSource::kStrain:
      return MismatchParameter::kStiffnessOrGaugeScale;
    case FusionSource::kAccelerometer:
    case FusionSource::kGyro: {
      // Total force wrong: the strain's forces or the mass. If the strain's
      // forces also disagree with the thrust map, the strain is wrong.
      double deviation = 0;
      for (int i = 0; i < rotors_; ++i) deviation = std::max(deviation, std::fabs(thrust_scale[i] - 1.0));
      return deviation > options_.thrust_scale_deviation ? MismatchParameter::kStiffnessOrGaugeScale
                                                         : MismatchParameter::kMass;
    }
  }
  return MismatchParameter::kNone;
}

}  // namespace birotor
