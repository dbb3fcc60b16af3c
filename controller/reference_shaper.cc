#include "controller/reference_shaper.h"

#include <algorithm>
#include <cmath>

namespace birotor {

void ReferenceShaper::Reset(const ReferencePoint& reference) {
  flown_ = reference;
  limiting_ = false;
}

bool ReferenceShaper::WithinLimits(const ReferencePoint& target, double dt_s) const {
  for (int axis = 0; axis < 2; ++axis) {
    const double step_m = std::fabs(target.position_m(axis) - flown_.position_m(axis));
    const double velocity_step_m_s = std::fabs(target.velocity_m_s(axis) - flown_.velocity_m_s(axis));
    if (step_m > limits_.max_speed_m_s * dt_s + limits_.position_tolerance_m) return false;
    if (velocity_step_m_s > limits_.max_accel_m_s2 * dt_s + limits_.velocity_tolerance_m_s) return false;
    if (std::fabs(target.velocity_m_s(axis)) > limits_.max_speed_m_s) return false;
    if (std::fabs(target.acceleration_m_s2(axis)) > limits_.max_accel_m_s2) return false;
  }
  return true;
}

bool ReferenceShaper::CaughtUp(const ReferencePoint& target) const {
  return (target.position_m - flown_.position_m).cwiseAbs().maxCoeff() <= limits_.position_tolerance_m &&
         (target.velocity_m_s - flown_.velocity_m_s).cwiseAbs().maxCoeff() <= limits_.velocity_tolerance_m_s;
}

void ReferenceShaper::LimitAxis(int axis, const ReferencePoint& target, double dt_s) {
  // Velocity that closes the gap e without overshoot: the target's own
  // velocity plus sign(e) min(sqrt(2 a_max |e|) - a_max dt, |e| / dt)
  // within +-v_max, reached with |dv| <= a_max dt; position by the
  // trapezoid of v. sqrt(2 a |e|) - a dt is the braking curve of this
  // discrete step: after a step that ends at v1 with deceleration a, the gap
  // left is e - (v1 + a dt / 2) dt, and it must hold v1^2 / (2 a).
  const double v_max = limits_.max_speed_m_s, a_max = limits_.max_accel_m_s2;
  const double gap_m = target.position_m(axis) - flown_.position_m(axis);
  const double braking_m_s = std::max(0.0, std::sqrt(2.0 * a_max * std::fabs(gap_m)) - a_max * dt_s);
  const double closing_m_s = std::min(braking_m_s, std::fabs(gap_m) / dt_s);
  const double wanted_m_s = std::clamp(
      std::clamp(target.velocity_m_s(axis), -v_max, v_max) + std::copysign(closing_m_s, gap_m), -v_max, v_max);
  const double v0 = flown_.velocity_m_s(axis);
  const double v1 = v0 + std::clamp(wanted_m_s - v0, -a_max * dt_s, a_max * dt_s);
  flown_.position_m(axis) += 0.5 * (v0 + v1) * dt_s;
  flown_.velocity_m_s(axis) = v1;
  flown_.acceleration_m_s2(axis) = (v1 - v0) / dt_s;
}

ReferencePoint ReferenceShaper::Step(const ReferencePoint& target, double dt_s) {
  if (!(dt_s > 0.0)) return flown_;  // the same period again (or a clock step back): as flown
  if (!limiting_ && WithinLimits(target, dt_s)) {
    flown_ = target;
    return flown_;
  }
  for (int axis = 0; axis < 2; ++axis) LimitAxis(axis, target, dt_s);
  ++limited_periods_;
  // Caught up with a target that moves within the limits: follow it exactly
  // again (a step of at most the tolerances).
  limiting_ = !(CaughtUp(target) && WithinLimits(target, dt_s));
  return flown_;
}

}  // namespace birotor
