#include "controller/hover_feasibility.h"

#include <algorithm>
#include <cmath>

#include "controller/position_attitude_law.h"
#include "controller/reference_point.h"

namespace birotor {
namespace {

// Lowest efficiency a latched weak rotor is flown with [1]: below it the map
// omega = sqrt(f / (e c_T)) puts the rotor at omega_max for any force it can
// make, so a lower value would only mislead the allocation.
constexpr double kMinEfficiency = 0.05;

// Recovery windows (sink_recover_s each) in a row that must show the margin.
constexpr int kRecoveryWindows = 2;

}  // namespace

HoverFeasibility::HoverFeasibility(const EfficiencyParams& params, double max_rotor_force_n, double weight_n)
    : params_(params), rotor_count_(2) {
  // margin (w / 2) / f_max == margin w / (2 f_max) exactly (halving is exact).
  for (int i = 0; i < rotor_count_; ++i) {
    bound_[i] = params.feasibility_margin * (0.5 * weight_n) / max_rotor_force_n;
    hover_speed_ratio_[i] = 1.0;  // equal rotors: the raw commands compare
  }
}

HoverFeasibility::HoverFeasibility(const EfficiencyParams& params, int rotor_count, const double* max_rotor_force_n,
                                   const double* hover_force_n, const HoverSpace& space)
    : params_(params),
      rotor_count_(std::clamp(rotor_count, 1, kMaxArms)),
      space_(space),
      tilted_max_share_(1.0 / params.feasibility_margin) {
  for (int i = 0; i < rotor_count_; ++i) {
    bound_[i] = params.feasibility_margin * hover_force_n[i] / max_rotor_force_n[i];
    hover_speed_ratio_[i] = std::sqrt(hover_force_n[i] / max_rotor_force_n[i]);
  }
}

void HoverFeasibility::Latch(Cause cause, int weak_rotor, double efficiency) {
  cause_ = cause;
  weak_rotor_ = weak_rotor;
  weak_efficiency_ = efficiency;
  phase_ = Phase::kLevelling;
}

void HoverFeasibility::MeasureRecovery(double omega_max_rad_s, double gravity_m_s2) {
  omega_max_rad_s_ = omega_max_rad_s;
  gravity_m_s2_ = gravity_m_s2;
}

void HoverFeasibility::Recover() {
  phase_ = Phase::kFeasible;
  cause_ = Cause::kNone;
  holds_weak_ = true;
  below_bound_s_ = sinking_s_ = 0.0;
  hold_elapsed_s_ = -1.0;
  hold_windows_ = 0;
  sink_armed_ = false;
  ++recoveries_;
}

bool HoverFeasibility::HoldMeasured(const FeasibilityInputs& in, double dt_s) {
  if (params_.sink_recover_s <= 0.0 || omega_max_rad_s_ <= 0.0) return false;
  const bool calm = std::fabs(in.tilt_rad) <= params_.level_tilt_rad &&
                    std::fabs(in.pitch_rate_rad_s) <= params_.level_rate_rad_s &&
                    in.climb_rate_m_s < -params_.recover_min_sink_m_s;
  if (!calm) {
    hold_elapsed_s_ = -1.0;
    hold_windows_ = 0;
    return false;
  }
  if (hold_elapsed_s_ < 0.0) {  // the window opens at this climb rate and height
    hold_elapsed_s_ = 0.0;
    hold_start_climb_m_s_ = in.climb_rate_m_s;
    hold_start_altitude_m_ = in.altitude_m;
    std::fill(hold_share_s_, hold_share_s_ + kMaxArms, 0.0);
    return false;
  }
  hold_elapsed_s_ += dt_s;
  double worst_share = 0.0;
  for (int i = 0; i < rotor_count_; ++i) {
    const double ratio = in.command_rad_s[i] / omega_max_rad_s_;
    hold_share_s_[i] += ratio * ratio * dt_s;
    worst_share = std::max(worst_share, hold_share_s_[i]);
  }
  if (hold_elapsed_s_ < params_.sink_recover_s) return false;
  // Mean vertical acceleration a_z and the busiest rotor's mean share s:
  // the rotors make m (g + a_z) at s of their maximum, so hover needs
  // (g + a_z) / (g s) >= margin (no division: s may be 0). The height
  // (POSE) must have dropped too: on the ground the observer's climb rate
  // decays for a while after the impact, the height does not move.
  const double accel_m_s2 = (in.climb_rate_m_s - hold_start_climb_m_s_) / hold_elapsed_s_;
  const double mean_share = worst_share / hold_elapsed_s_;
  const bool dropped = in.altitude_m - hold_start_altitude_m_ <= -params_.recover_min_sink_m_s * hold_elapsed_s_;
  const bool held = dropped && gravity_m_s2_ + accel_m_s2 >= params_.feasibility_margin * gravity_m_s2_ * mean_share;
  hold_elapsed_s_ = -1.0;  // the next window
  // Two windows in a row: an impact on the ground fills at most one (its
  // stop reads as a large a_z), the next one is on the ground.
  hold_windows_ = held ? hold_windows_ + 1 : 0;
  return hold_windows_ >= kRecoveryWindows;
}

double HoverFeasibility::EfficiencyFor(int rotor, double efficiency_in_use) const {
  return (infeasible() || holds_weak_) && rotor == weak_rotor_ ? weak_efficiency_ : efficiency_in_use;
}

int HoverFeasibility::Weakest(const double (&efficiency)[kMaxArms]) const {
  int weakest = 0;
  for (int i = 1; i < rotor_count_; ++i) {
    // e_i / b_i < e_w / b_w without dividing (equal bounds: e_i < e_w).
    if (efficiency[i] * bound_[weakest] < efficiency[weakest] * bound_[i]) weakest = i;
  }
  return weakest;
}

double HoverFeasibility::Evidence(const FeasibilityInputs& in, int rotor) const {
  const double report = in.below_floor_report[rotor];
  return space_.rebalances() && std::isfinite(report) ? std::min(in.efficiency[rotor], report) : in.efficiency[rotor];
}

bool HoverFeasibility::HoverHeld(const FeasibilityInputs& in, int weakest) const {
  // margin f_hover,i > e_i c_T,i omega_max^2 for some i  <=>  e_i < bound_i.
  const bool level_held = !(in.efficiency[weakest] < bound_[weakest]);
  if (!space_.rebalances() || (level_held && !space_.redundant())) return level_held;
  double efficiency[kMaxArms];
  for (int i = 0; i < kMaxArms; ++i) efficiency[i] = Evidence(in, i);
  const double max_share = 1.0 / params_.feasibility_margin;
  // Without a spare rotor the only hovers besides f_hover are the tilted ones.
  if (space_.redundant()) {
    return space_.NearestWithinShares(efficiency, params_.spare_min_share, max_share, nullptr) ||
           space_.NearestTiltedWithinShares(efficiency, params_.spare_min_share, max_share,
                                            params_.spare_hover_tilt_rad, nullptr, nullptr);
  }
  return space_.NearestTiltedWithinShares(efficiency, params_.spare_min_share, tilted_max_share_,
                                          params_.spare_hover_tilt_rad, nullptr, nullptr);
}

int HoverFeasibility::WeakFromSink(const FeasibilityInputs& in) const {
  int lowest = 0;
  int highest = 0;
  int hardest = 0;
  for (int i = 1; i < rotor_count_; ++i) {
    if (in.reported_scale[i] < in.reported_scale[lowest]) lowest = i;
    if (in.reported_scale[i] > in.reported_scale[highest]) highest = i;
    // omega_i / omega_hover,i: on the birotor (equal hover speeds) the raw commands.
    if (in.command_rad_s[i] * hover_speed_ratio_[hardest] > in.command_rad_s[hardest] * hover_speed_ratio_[i])
      hardest = i;
  }
  const bool reported_apart = in.reported_scale[highest] - in.reported_scale[lowest] > params_.change_threshold;
  return reported_apart ? lowest : hardest;
}

HoverFeasibility::Phase HoverFeasibility::Update(const FeasibilityInputs& in, double dt_s) {
  const int weakest = Weakest(in.efficiency);
  if (infeasible() && cause_ == Cause::kSink && HoldMeasured(in, dt_s)) Recover();
  holds_weak_ = holds_weak_ && !in.following_force;
  if (infeasible()) {
    // Latched: the weak rotor stays infeasible; its efficiency follows a
    // usable FORCE (a transient low of the ringing estimate is not kept),
    // and holds while FORCE is unusable (MODEL_MISMATCH, stale: the fallback
    // decays the estimate towards 1). Detected from the sink, FORCE was at
    // its floor: only a lower estimate is taken.
    if (in.following_force) {
      const double followed = std::min(in.efficiency[weak_rotor_], bound_[weak_rotor_]);
      weak_efficiency_ = cause_ == Cause::kSink ? std::min(weak_efficiency_, followed) : followed;
    }
    if (phase_ == Phase::kLevelling && std::fabs(in.tilt_rad) <= params_.level_tilt_rad &&
        std::fabs(in.pitch_rate_rad_s) <= params_.level_rate_rad_s) {
      phase_ = Phase::kDescending;
    }
    return phase_;
  }
  below_bound_s_ = in.relative_efficiency || HoverHeld(in, weakest) ? 0.0 : below_bound_s_ + dt_s;
  const bool behind = in.altitude_lag_m > params_.sink_detect_altitude_m && in.sink_behind_m_s > 0.0;
  sink_armed_ = sink_armed_ || !behind;
  const bool sinking = sink_armed_ && in.allocation_limited && behind;
  if (sinking && sinking_s_ == 0.0) sink_start_climb_m_s_ = in.climb_rate_m_s;
  sinking_s_ = sinking ? sinking_s_ + dt_s : 0.0;
  // The sink grows over the window: the rotors, limited, do not hold the weight.
  const bool sink_grows = in.climb_rate_m_s < sink_start_climb_m_s_;
  if (sinking_s_ >= params_.sink_detect_s && !sink_grows) sinking_s_ = 0.0;  // the next window opens next period
  if (below_bound_s_ > 0.0 && below_bound_s_ >= params_.infeasible_s) {
    Latch(Cause::kEfficiency, weakest, in.efficiency[weakest]);
  } else if (sinking_s_ > 0.0 && sinking_s_ >= params_.sink_detect_s) {
    // The vehicle cannot hold its height with the allocation at its limit:
    // the weak rotor's efficiency at most FORCE's report (a sample refused
    // at the floor says "at most the floor") and at most the bound (it is
    // infeasible).
    const int weak = WeakFromSink(in);
    const double reported = std::isfinite(in.reported_scale[weak]) ? in.reported_scale[weak] : bound_[weak];
    Latch(Cause::kSink, weak, std::clamp(std::min(in.efficiency[weak], reported), kMinEfficiency, bound_[weak]));
    ++entries_by_sink_;
  }
  return phase_;
}

void SetTrackingInputs(const ReferencePoint& reference, const BodyState& body, FeasibilityInputs* in) {
  in->altitude_lag_m = reference.position_m.y() - body.position_m.y();
  in->sink_behind_m_s = reference.velocity_m_s.y() - body.velocity_m_s.y();
  in->tilt_rad = body.phi_rad;
  in->pitch_rate_rad_s = body.phi_dot_rad_s;
  in->climb_rate_m_s = body.velocity_m_s.y();
  in->altitude_m = body.position_m.y();
}

}  // namespace birotor
