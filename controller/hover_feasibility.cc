#include "controller/hover_feasibility.h"

#include <algorithm>
#include <cmath>

namespace birotor {
namespace {

// Lowest efficiency a latched weak rotor is flown with [1]: below it the map
// omega = sqrt(f / (e c_T)) puts the rotor at omega_max for any force it can
// make, so a lower value would only mislead the allocation.
constexpr double kMinEfficiency = 0.05;

}  // namespace

HoverFeasibility::HoverFeasibility(const EfficiencyParams& params, double max_rotor_force_n, double weight_n)
    : params_(params), bound_(params.feasibility_margin * weight_n / (2.0 * max_rotor_force_n)) {}

void HoverFeasibility::Latch(Cause cause, int weak_rotor, double efficiency) {
  cause_ = cause;
  weak_rotor_ = weak_rotor;
  weak_efficiency_ = efficiency;
  phase_ = Phase::kLevelling;
}

double HoverFeasibility::EfficiencyFor(int rotor, double efficiency_in_use) const {
  return infeasible() && rotor == weak_rotor_ ? weak_efficiency_ : efficiency_in_use;
}

HoverFeasibility::Phase HoverFeasibility::Update(const FeasibilityInputs& in, double dt_s) {
  const int weakest = in.efficiency[1] < in.efficiency[0] ? 1 : 0;
  if (infeasible()) {
    // Latched: the weak rotor stays infeasible; its efficiency follows a
    // usable FORCE (a transient low of the ringing estimate is not kept),
    // and holds while FORCE is unusable (MODEL_MISMATCH, stale: the fallback
    // decays the estimate towards 1). Detected from the sink, FORCE was at
    // its floor: only a lower estimate is taken.
    if (in.following_force) {
      const double followed = std::min(in.efficiency[weak_rotor_], bound_);
      weak_efficiency_ = cause_ == Cause::kSink ? std::min(weak_efficiency_, followed) : followed;
    }
    if (phase_ == Phase::kLevelling && std::fabs(in.tilt_rad) <= params_.level_tilt_rad &&
        std::fabs(in.pitch_rate_rad_s) <= params_.level_rate_rad_s) {
      phase_ = Phase::kDescending;
    }
    return phase_;
  }
  // 2 min_i(e_i c_T omega_max^2) < margin x weight  <=>  min_i e_i < bound.
  below_bound_s_ = in.efficiency[weakest] < bound_ ? below_bound_s_ + dt_s : 0.0;
  const bool sinking =
      in.allocation_limited && in.altitude_lag_m > params_.sink_detect_altitude_m && in.sink_behind_m_s > 0.0;
  sinking_s_ = sinking ? sinking_s_ + dt_s : 0.0;
  if (below_bound_s_ > 0.0 && below_bound_s_ >= params_.infeasible_s) {
    Latch(Cause::kEfficiency, weakest, in.efficiency[weakest]);
  } else if (sinking_s_ > 0.0 && sinking_s_ >= params_.sink_detect_s) {
    // The vehicle cannot hold its height with the allocation at its limit:
    // the weaker rotor by FORCE's report when it tells them apart (a sample
    // refused at the floor says "at most the floor"), else the one the
    // attitude loop drives harder; its efficiency at most that report and at
    // most the bound (it is infeasible).
    const bool reported_apart = std::fabs(in.reported_scale[1] - in.reported_scale[0]) > params_.change_threshold;
    const int weak = reported_apart ? (in.reported_scale[1] < in.reported_scale[0] ? 1 : 0)
                                    : (in.command_rad_s[1] > in.command_rad_s[0] ? 1 : 0);
    const double reported = std::isfinite(in.reported_scale[weak]) ? in.reported_scale[weak] : bound_;
    Latch(Cause::kSink, weak, std::clamp(std::min(in.efficiency[weak], reported), kMinEfficiency, bound_));
  }
  return phase_;
}

}  // namespace birotor
