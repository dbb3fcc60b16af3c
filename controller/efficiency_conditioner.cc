#include "controller/efficiency_conditioner.h"

#include <algorithm>
#include <cmath>

#include "numerics/time_units.h"

namespace birotor {

EfficiencyConditioner::EfficiencyConditioner(const EfficiencyParams& params, double weight_n, int rotor_count)
    : params_(params),
      weight_n_(weight_n),
      rotor_count_(std::clamp(rotor_count, 1, kMaxArms)),
      airborne_(params, weight_n, std::clamp(rotor_count, 1, kMaxArms)),
      mismatch_(params, weight_n, std::clamp(rotor_count, 1, kMaxArms)) {
  change_.fill(1.0);
  absolute_.fill(1.0);
  absolute_target_.fill(1.0);
  target_.fill(1.0);
  baseline_.fill(1.0);
  baseline_relative_std_.fill(1.0);
}

void EfficiencyConditioner::OnForce(const RotorEfficiencyEstimate& estimate) {
  if (!estimate.valid || estimate.n_rotors != rotor_count_) return;
  mismatch_.Reset();
  Take(estimate);
}

void EfficiencyConditioner::OnForce(const ForceEstimate& estimate) {
  if (rotor_count_ != kBirotorRotors) return;
  mismatch_.Reset();
  Take(RotorEfficiencyReportOf(estimate));
}

void EfficiencyConditioner::OnMismatchedForce(const RotorEfficiencyEstimate& estimate) {
  if (!params_.mismatch_relative || estimate.valid || !MismatchedOnly(estimate.status) ||
      estimate.n_rotors != rotor_count_)
    return;
  mismatch_.OnMismatchedReport(estimate);
}

void EfficiencyConditioner::OnMismatchedForce(const ForceEstimate& estimate) {
  if (rotor_count_ != kBirotorRotors) return;
  OnMismatchedForce(RotorEfficiencyReportOf(estimate));
}

void EfficiencyConditioner::Take(const RotorEfficiencyEstimate& e) {
  const double dt_s = last_utime_ < 0 ? 0.0 : ElapsedSeconds(e.utime, last_utime_);
  last_utime_ = e.utime;
  if (!airborne_.Note(e)) return;
  const bool deficit = (e.status & kStatusThrustDeficit) != 0;
  const double baseline_gain = std::min(1.0, dt_s / params_.baseline_tau_s);
  // A rotor's mean share of the hover thrust [N]: the sigma of a rotor that
  // makes (almost) nothing is judged against what it should make, not
  // against its own 0 (a dead rotor's 0.01 N, sigma 0.1 N, is certain).
  const double mean_hover_n = weight_n_ / rotor_count_;
  for (int i = 0; i < rotor_count_; ++i) {
    const size_t r = Index(i);
    // An uncertain sample is not followed: the target holds.
    const double reference_n = std::max(std::fabs(e.force_n[r]), mean_hover_n);
    if (!(e.force_std_n[r] <= params_.max_relative_sigma * reference_n)) continue;
    const double relative_std = e.force_std_n[r] / reference_n;
    if (!has_baseline_) {
      baseline_[r] = e.thrust_scale[r];
      baseline_relative_std_[r] = relative_std;
    }
    // A change is real when the estimate flags it, or when it is larger
    // than change_threshold relative to the baseline; neither counts before
    // the baseline has settled (a mismatch flagged from take-off on).
    const bool settled = settled_s_ >= params_.baseline_tau_s;
    flagged_[r] = settled && (deficit || (e.rotor_fault_bits & (1 << i)) != 0 ||
                              std::fabs(e.thrust_scale[r] / baseline_[r] - 1.0) > params_.change_threshold);
    if (!flagged_[r]) {
      baseline_[r] += baseline_gain * (e.thrust_scale[r] - baseline_[r]);
      baseline_relative_std_[r] += baseline_gain * (relative_std - baseline_relative_std_[r]);
    }
    target_[r] = flagged_[r] ? std::min(e.thrust_scale[r] / baseline_[r], params_.max_change_gain) : 1.0;
  }
  has_baseline_ = true;
  settled_s_ += std::min(dt_s, 0.1);  // a gap does not count
  NoteAbsolute(e);
}

void EfficiencyConditioner::NoteAbsolute(const RotorEfficiencyEstimate& e) {
  // The caller passes VALID samples only; MODEL_MISMATCH withdraws VALID, the
  // bit is tested again so the rule does not rest on the caller.
  const bool estimator_sure = (e.status & (kStatusModelMismatch | kStatusConverging)) == 0;
  const bool settled = settled_s_ >= params_.absolute_settle_s;
  for (int i = 0; i < rotor_count_; ++i) {
    const size_t r = Index(i);
    const bool precise = e.force_std_n[r] <= params_.absolute_max_relative_sigma * std::fabs(e.force_n[r]);
    trusted_[r] = params_.absolute_tau_s > 0.0 && settled && estimator_sure && precise;
    if (!trusted_[r]) continue;
    // A matched vehicle's mu0 wanders by a few per cent (noise, turbulence):
    // left to the integrators. A vehicle off the map by more than
    // absolute_threshold, and by more than absolute_min_sigmas of what mu0
    // is known to (a converging filter's early mu0 is off by its wide
    // sigma), is flown on mu0 until it is back within half of the threshold
    // (hysteresis: no toggling at the threshold). While rotor i is flagged
    // its baseline holds, and so does this target.
    const double offset = std::fabs(baseline_[r] - 1.0);
    const bool significant = offset > params_.absolute_min_sigmas * baseline_relative_std_[r];
    if (offset > params_.absolute_threshold && significant) absolute_engaged_[r] = true;
    if (offset < 0.5 * params_.absolute_threshold) absolute_engaged_[r] = false;
    absolute_target_[r] = absolute_engaged_[r] ? std::clamp(baseline_[r], params_.min_absolute_efficiency,
                                                            params_.max_absolute_efficiency)
                                               : 1.0;
  }
}

void EfficiencyConditioner::Advance(double dt_s, bool usable, bool change_usable) {
  const bool follow = usable && airborne_.airborne() && has_baseline_;
  // Not VALID by MODEL_MISMATCH alone: a change the rule confirmed is flown.
  const bool relative = !follow && change_usable;
  relative_since_usable_ = !follow && relative_since_usable_;
  // Back from a fallback longer than blend_after_s: the integrators have
  // absorbed what the estimate could not tell, so it is blended in over
  // blend_s instead of at once (a short dropout returns at once).
  if (follow && !was_following_ && unusable_s_ >= params_.blend_after_s) blend_left_s_ = params_.blend_s;
  unusable_s_ = follow ? 0.0 : unusable_s_ + dt_s;
  was_following_ = follow;
  const double flagged_tau_s =
      blend_left_s_ > 0.0 ? std::max(params_.fault_tau_s, params_.blend_s / 3.0) : params_.fault_tau_s;
  blend_left_s_ = std::max(0.0, blend_left_s_ - dt_s);
  const double max_step = params_.max_rate_1_s * dt_s;
  for (int i = 0; i < rotor_count_; ++i) {
    const size_t r = Index(i);
    const bool flagged = follow && flagged_[r];
    const bool flown_relative = relative && mismatch_.flown(i);
    relative_since_usable_ = relative_since_usable_ || flown_relative;
    const double goal = flown_relative ? mismatch_.target(i) : flagged ? target_[r] : 1.0;
    const double tau_s = flown_relative ? std::max(params_.fault_tau_s, mismatch_.handover_tau_s(i))
                         : flagged      ? flagged_tau_s
                                        : params_.decay_s;
    const double step = (goal - change_[r]) * std::min(1.0, dt_s / tau_s);
    change_[r] += std::clamp(step, -max_step, max_step);
    // The absolute factor: towards the trusted mu0_i slowly, else towards 1
    // as the change factor decays (continuous both ways).
    const bool trusted = follow && trusted_[r];
    const double absolute_goal = trusted ? absolute_target_[r] : 1.0;
    const double absolute_tau_s = trusted ? params_.absolute_tau_s : params_.decay_s;
    const double absolute_step = (absolute_goal - absolute_[r]) * std::min(1.0, dt_s / absolute_tau_s);
    absolute_[r] += std::clamp(absolute_step, -max_step, max_step);
  }
}

}  // namespace birotor
