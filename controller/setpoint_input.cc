#include "controller/setpoint_input.h"

#include <algorithm>
#include <cmath>

#include "numerics/time_units.h"

namespace birotor {
namespace {

bool FiniteWithin(double value, double limit) { return std::isfinite(value) && std::fabs(value) <= limit; }
// A feed-forward may be NaN (not given); otherwise within the limit.
bool AbsentOrWithin(double value, double limit) { return std::isnan(value) || FiniteWithin(value, limit); }

}  // namespace

void SetpointInput::SetStart(const Eigen::Vector2d& position_m) {
  hold_m_ = position_m;
  last_reference_ = ReferencePoint();
  last_reference_.position_m = position_m;
}

bool SetpointInput::Plausible(const Setpoint& s) const {
  const SetpointParams& p = params_;
  return FiniteWithin(s.x_m, p.max_abs_position_m) && FiniteWithin(s.z_m, p.max_abs_position_m) &&
         AbsentOrWithin(s.x_dot_m_s, p.max_speed_m_s) && AbsentOrWithin(s.z_dot_m_s, p.max_speed_m_s) &&
         AbsentOrWithin(s.x_ddot_m_s2, p.max_accel_m_s2) && AbsentOrWithin(s.z_ddot_m_s2, p.max_accel_m_s2);
}

bool SetpointInput::Offer(const Setpoint& setpoint, int64_t now_us) {
  ++counters_.received;
  if (!Plausible(setpoint)) {
    ++counters_.rejected_invalid;
    return false;
  }
  const double age_s = ElapsedSeconds(now_us, setpoint.utime);
  if (age_s > params_.timeout_s || -age_s > params_.future_window_s) {
    ++counters_.rejected_stamp;
    return false;
  }
  if (has_setpoint_) {
    if (setpoint.utime <= newest_.utime) {
      ++counters_.rejected_out_of_order;
      return false;
    }
    if (ElapsedSeconds(setpoint.utime, newest_.utime) < params_.min_interval_s) {
      ++counters_.rejected_rate;
      return false;
    }
  }
  if ((Eigen::Vector2d(setpoint.x_m, setpoint.z_m) - last_reference_.position_m).norm() > params_.max_jump_m) {
    ++counters_.rejected_jump;
    return false;
  }
  ++counters_.accepted;
  newest_ = setpoint;
  has_setpoint_ = true;
  return true;
}

ReferencePoint SetpointInput::At(int64_t now_us, const Eigen::Vector2d& position_m) {
  ReferencePoint reference;
  if (has_setpoint_) {
    const double age_s = ElapsedSeconds(now_us, newest_.utime);
    if (age_s <= params_.timeout_s) {
      state_ = SetpointState::kFollowing;
      last_reference_ = ReferenceFromSetpoint(newest_, std::clamp(age_s, 0.0, params_.max_extrapolation_s));
      if (age_s > params_.max_extrapolation_s) {
        // Held without feed-forward: a stale velocity would drag the body.
        last_reference_.velocity_m_s.setZero();
        last_reference_.acceleration_m_s2.setZero();
      }
      return last_reference_;
    }
    if (state_ == SetpointState::kFollowing) {
      state_ = SetpointState::kHoldHere;
      ++counters_.timeouts;
      hold_m_ = position_m;
    }
  }
  reference.position_m = hold_m_;
  last_reference_ = reference;
  return reference;
}

}  // namespace birotor
