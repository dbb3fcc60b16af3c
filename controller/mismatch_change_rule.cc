#include "controller/mismatch_change_rule.h"

#include <algorithm>
#include <cmath>

#include "numerics/time_units.h"

namespace birotor {

MismatchChangeRule::MismatchChangeRule(const EfficiencyParams& params, double weight_n, int rotor_count)
    : params_(params),
      weight_n_(weight_n),
      rotor_count_(std::clamp(rotor_count, 1, kMaxArms)),
      airborne_(params, weight_n, std::clamp(rotor_count, 1, kMaxArms)) {
  baseline_.fill(1.0);
}

void MismatchChangeRule::Reset() {
  has_baseline_ = false;
  settled_s_ = 0.0;
  distrusted_ = false;
  faulted_rotors_ = 0;
  flown_.fill(false);
  change_.fill(0.0);
  fault_held_s_.fill(0.0);
  confirming_s_.fill(0.0);
  handover_tau_s_.fill(0.0);
}

bool MismatchChangeRule::CommonFactor(const RotorEfficiencyEstimate& e, const std::array<bool, kMaxArms>& precise,
                                      double* common) const {
  double sum = 0.0;
  int unflagged = 0;
  for (int i = 0; i < rotor_count_; ++i) {
    const size_t r = Index(i);
    if (!precise[r] || flown_[r] || (e.rotor_fault_bits & (1 << i)) != 0) continue;
    sum += e.thrust_scale[r] / baseline_[r];
    ++unflagged;
  }
  if (unflagged == 0 || !(sum > 0.0)) return false;
  *common = sum / unflagged;
  return true;
}

void MismatchChangeRule::OnMismatchedReport(const RotorEfficiencyEstimate& e) {
  const double dt_s = last_utime_ < 0 ? 0.0 : std::min(ElapsedSeconds(e.utime, last_utime_), 0.1);
  last_utime_ = e.utime;
  if (!airborne_.Note(e)) return;
  const double mean_hover_n = weight_n_ / rotor_count_;
  std::array<bool, kMaxArms> precise{};
  for (int i = 0; i < rotor_count_; ++i) {
    const size_t r = Index(i);
    precise[r] = PreciseEnough(e.force_n[r], e.force_std_n[r], mean_hover_n, params_.max_relative_sigma);
    if (precise[r] && !has_baseline_) baseline_[r] = e.thrust_scale[r];
  }
  has_baseline_ = true;
  // Faults on more than one rotor in this episode: the flags disagree; a
  // fault before the baselines settled: they may hold it already.
  const int32_t faults = e.rotor_fault_bits & ((1 << rotor_count_) - 1);
  const bool settled = settled_s_ >= params_.baseline_tau_s;
  faulted_rotors_ |= faults;
  distrusted_ = distrusted_ || (faulted_rotors_ & (faulted_rotors_ - 1)) != 0 || (!settled && faults != 0);
  double common = 1.0;
  const bool comparable = settled && !distrusted_ && CommonFactor(e, precise, &common);
  bool any_flown = false;
  for (int i = 0; i < rotor_count_; ++i) {
    const size_t r = Index(i);
    if (!precise[r]) continue;
    change_[r] = comparable ? e.thrust_scale[r] / baseline_[r] / common - 1.0 : 0.0;
    if (comparable) Judge(i, (e.rotor_fault_bits & (1 << i)) != 0, change_[r], common, dt_s);
    flown_[r] = flown_[r] && comparable && !distrusted_ && std::fabs(change_[r]) > params_.change_threshold;
    any_flown = any_flown || flown_[r];
  }
  // The baselines follow, none while a fault is flagged or a change flown
  // (it is relative to theirs).
  const double gain = std::min(1.0, dt_s / params_.baseline_tau_s);
  for (int i = 0; i < rotor_count_ && !any_flown && faults == 0; ++i) {
    const size_t r = Index(i);
    if (precise[r]) baseline_[r] += gain * (e.thrust_scale[r] - baseline_[r]);
  }
  settled_s_ += dt_s;
}

void MismatchChangeRule::Judge(int rotor, bool fault, double change, double common, double dt_s) {
  const size_t r = Index(rotor);
  fault_held_s_[r] = fault ? fault_held_s_[r] + dt_s : 0.0;
  if (flown_[r]) {
    distrusted_ = distrusted_ || std::fabs(change - confirmed_change_[r]) > params_.mismatch_max_spread;
    return;
  }
  if (!fault || change >= -params_.mismatch_min_change) {
    confirming_s_[r] = 0.0;
    return;
  }
  // Steady: the change and the others' common factor each within
  // mismatch_max_spread over the run; a sample that breaks it starts a new run.
  RunSpan& run = runs_[r];
  const bool steady = confirming_s_[r] > 0.0 && run.change.Within(change, params_.mismatch_max_spread) &&
                      run.common.Within(common, params_.mismatch_max_spread);
  if (!steady) {
    confirming_s_[r] = 0.0;
    run = RunSpan{{change, change}, {common, common}};
  }
  confirming_s_[r] += dt_s;
  run.change.Add(change);
  run.common.Add(common);
  if (confirming_s_[r] < params_.mismatch_confirm_s) return;
  // At once, the integrators' share would be flown twice: a tilt the other way.
  flown_[r] = true;
  confirmed_change_[r] = change;
  handover_tau_s_[r] = params_.mismatch_handover_factor * fault_held_s_[r];
}

}  // namespace birotor
