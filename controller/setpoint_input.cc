#include "controller/setpoint_input.h"

#include <algorithm>
#include <cmath>

#include "numerics/time_units.h"

namespace birotor {
namespace {

constexpr double kMaxShapingStepS = 0.05;  // [s]; 10 periods of the 200 Hz mpc

bool FiniteWithin(double value, double limit) { return std::isfinite(value) && std::fabs(value) <= limit; }
// A feed-forward may be NaN (not given); otherwise within the limit.
bool AbsentOrWithin(double value, double limit) { return std::isnan(value) || FiniteWithin(value, limit); }

// One axis: the new setpoint's feed-forward rate1 (trapezoid with the
// previous one's rate0, or rate1 alone when rate0 was not given) against the
// change it integrates into: |mean rate dt - change| <= tolerance window.
// Not checked (true) when rate1 is not given (NaN: not flown) or the change
// is unknown (NaN: a velocity not given).
bool RateAgrees(double rate0, double rate1, double change, double dt_s, double tolerance, double window_s) {
  if (std::isnan(rate1) || std::isnan(change)) return true;
  const double mean = std::isnan(rate0) ? rate1 : 0.5 * (rate0 + rate1);
  return std::fabs(mean * dt_s - change) <= tolerance * window_s;
}

// The velocity feed-forward against the change of position, when both
// setpoints gave it (after a position-only setpoint it has no partner).
bool VelocityAgrees(double v0, double v1, double change_m, double dt_s, double tolerance, double window_s) {
  return std::isnan(v0) || RateAgrees(v0, v1, change_m, dt_s, tolerance, window_s);
}

}  // namespace

ShaperLimits ShaperLimitsOf(const SetpointParams& p) {
  return ShaperLimits{p.max_speed_m_s, p.max_accel_m_s2, p.shaping_position_tolerance_m,
                      p.shaping_velocity_tolerance_m_s, p.shaping_bandwidth_rad_s};
}

PublisherLockRule PublisherLockRuleOf(const SetpointParams& p) {
  return PublisherLockRule{p.lock_max_rate_hz, p.lock_rate_margin, p.lock_seq_slack, p.lock_stamp_slack_s,
                           p.conflict_hold_s};
}

SetpointCounters SetpointInput::counters() const {
  SetpointCounters c = counters_;
  c.conflicts = lock_.conflicts();
  c.limited_periods = shaper_.limited_periods();
  return c;
}

void SetpointInput::SetStart(const Eigen::Vector2d& position_m) {
  hold_m_ = position_m;
  started_ = true;
  ReferencePoint start;
  start.position_m = position_m;
  shaper_.Reset(start);
}

bool SetpointInput::Plausible(const Setpoint& s) const {
  const SetpointParams& p = params_;
  return FiniteWithin(s.x_m, p.max_abs_position_m) && FiniteWithin(s.z_m, p.max_abs_position_m) &&
         AbsentOrWithin(s.x_dot_m_s, p.max_feed_forward_speed_m_s) &&
         AbsentOrWithin(s.z_dot_m_s, p.max_feed_forward_speed_m_s) &&
         AbsentOrWithin(s.x_ddot_m_s2, p.max_feed_forward_accel_m_s2) &&
         AbsentOrWithin(s.z_ddot_m_s2, p.max_feed_forward_accel_m_s2);
}

bool SetpointInput::FeedForwardConsistent(const Setpoint& s) const {
  // An acceleration without the velocity it integrates into cannot be checked: refused.
  if ((!std::isnan(s.x_ddot_m_s2) && std::isnan(s.x_dot_m_s)) ||
      (!std::isnan(s.z_ddot_m_s2) && std::isnan(s.z_dot_m_s)))
    return false;
  const SetpointParams& p = params_;
  const Setpoint& o = newest_;
  const double dt_s = ElapsedSeconds(s.utime, o.utime);  // > 0: the order check came first
  if (!has_setpoint_) return true;                       // nothing to compare the first with
  const double window_s = std::max(dt_s, p.ff_interval_floor_s);
  const double tol_v = p.ff_velocity_tolerance_m_s, tol_a = p.ff_accel_tolerance_m_s2;
  return VelocityAgrees(o.x_dot_m_s, s.x_dot_m_s, s.x_m - o.x_m, dt_s, tol_v, window_s) &&
         VelocityAgrees(o.z_dot_m_s, s.z_dot_m_s, s.z_m - o.z_m, dt_s, tol_v, window_s) &&
         RateAgrees(o.x_ddot_m_s2, s.x_ddot_m_s2, s.x_dot_m_s - o.x_dot_m_s, dt_s, tol_a, window_s) &&
         RateAgrees(o.z_ddot_m_s2, s.z_ddot_m_s2, s.z_dot_m_s - o.z_dot_m_s, dt_s, tol_a, window_s);
}

bool SetpointInput::InTimeFromTheLockedPublisher(const Setpoint& s, int64_t now_us) {
  const double age_s = ElapsedSeconds(now_us, s.utime);
  if (age_s > params_.timeout_s || -age_s > params_.future_window_s) {
    ++counters_.rejected_stamp;
    return false;
  }
  if (lock_.Offer(s.seq, s.utime, now_us) == PublisherVerdict::kConflict) {
    ++counters_.rejected_conflict;
    return false;
  }
  if (has_setpoint_) {
    if (s.utime <= newest_.utime) {
      ++counters_.rejected_out_of_order;
      return false;
    }
    if (ElapsedSeconds(s.utime, newest_.utime) < params_.min_interval_s) {
      ++counters_.rejected_rate;
      return false;
    }
  }
  return true;
}

bool SetpointInput::Offer(const Setpoint& setpoint, int64_t now_us) {
  ++counters_.received;
  if (!Plausible(setpoint)) {
    ++counters_.rejected_invalid;
    return false;
  }
  if (!InTimeFromTheLockedPublisher(setpoint, now_us)) return false;
  if ((Eigen::Vector2d(setpoint.x_m, setpoint.z_m) - shaper_.flown().position_m).norm() > params_.max_jump_m) {
    ++counters_.rejected_jump;
    return false;
  }
  if (!FeedForwardConsistent(setpoint)) {
    ++counters_.rejected_inconsistent;
    return false;
  }
  ++counters_.accepted;
  newest_ = setpoint;
  has_setpoint_ = true;
  return true;
}

ReferencePoint SetpointInput::Target(int64_t now_us, const Eigen::Vector2d& position_m) {
  ReferencePoint hold;
  if (lock_.InConflict(now_us)) {
    // Two publishers: neither is followed; hover at the reference flown then.
    if (!holding_for_conflict_) conflict_hold_m_ = shaper_.flown().position_m;
    holding_for_conflict_ = true;
    hold.position_m = conflict_hold_m_;
    return hold;
  }
  holding_for_conflict_ = false;
  if (has_setpoint_) {
    const double age_s = ElapsedSeconds(now_us, newest_.utime);
    if (age_s <= params_.timeout_s) {
      state_ = SetpointState::kFollowing;
      ReferencePoint target = ReferenceFromSetpoint(newest_, std::clamp(age_s, 0.0, params_.max_extrapolation_s));
      if (age_s > params_.max_extrapolation_s) {
        // Held without feed-forward: a stale velocity would drag the body.
        target.velocity_m_s.setZero();
        target.acceleration_m_s2.setZero();
      }
      return target;
    }
    if (state_ == SetpointState::kFollowing) {
      state_ = SetpointState::kHoldHere;
      ++counters_.timeouts;
      hold_m_ = position_m;
    }
  }
  hold.position_m = hold_m_;
  return hold;
}

ReferencePoint SetpointInput::At(int64_t now_us, const Eigen::Vector2d& position_m) {
  const ReferencePoint target = Target(now_us, position_m);
  if (last_at_us_ < 0) {
    // The first period: the target when it is within start_snap_m of the
    // start position (the first POSE, with its noise) and within the limits;
    // another (a setpoint before the first period) is approached from the
    // start, shaped.
    const bool near_start = (target.position_m - shaper_.flown().position_m).norm() <= params_.start_snap_m &&
                            target.velocity_m_s.cwiseAbs().maxCoeff() <= params_.max_speed_m_s &&
                            target.acceleration_m_s2.cwiseAbs().maxCoeff() <= params_.max_accel_m_s2;
    if (!started_ || near_start) shaper_.Reset(target);
    last_at_us_ = now_us;
    return shaper_.flown();
  }
  // A gap between periods (no POSE, a paused process) counts as at most
  // kMaxShapingStepS: the shaping model is integrated explicitly (stable
  // for w dt < 2) and the allowances of the limits grow with dt.
  const double dt_s = std::min(ElapsedSeconds(now_us, last_at_us_), kMaxShapingStepS);
  last_at_us_ = std::max(last_at_us_, now_us);
  return shaper_.Step(target, dt_s);
}

}  // namespace birotor
