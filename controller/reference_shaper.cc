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

// Within the position tolerance, and a velocity step the acceleration limit
// allows in one period.
bool ReferenceShaper::CaughtUp(const ReferencePoint& target, double dt_s) const {
  return (target.position_m - flown_.position_m).cwiseAbs().maxCoeff() <= limits_.position_tolerance_m &&
         (target.velocity_m_s - flown_.velocity_m_s).cwiseAbs().maxCoeff() <= limits_.max_accel_m_s2 * dt_s;
}

void ReferenceShaper::LimitAxis(int axis, const ReferencePoint& target, double dt_s) {
  // A critically damped reference model towards the target, saturated:
  //   a = clamp(a_t + w^2 (p_t - p) + 2 w (v_t - v), +-a_max),
  //   v1 = clamp(v0 + a dt, +-v_max),  p1 = p0 + (v0 + v1) / 2 dt.
  // Linear inside the limits, so its acceleration turns from speeding up to
  // braking continuously (a bang-bang reversal of 2 a_max kicks the tilt);
  // it brakes from e < 2 v / w on, before the v^2 / (2 a_max) it needs
  // while w <= 4 a_max / v_max.
  const double w = limits_.bandwidth_rad_s;
  const double a_max = limits_.max_accel_m_s2, v_max = limits_.max_speed_m_s;
  const double gap_m = target.position_m(axis) - flown_.position_m(axis);
  const double velocity_gap_m_s = target.velocity_m_s(axis) - flown_.velocity_m_s(axis);
  const double wanted_m_s2 =
      std::clamp(target.acceleration_m_s2(axis) + w * w * gap_m + 2.0 * w * velocity_gap_m_s, -a_max, a_max);
  const double v0 = flown_.velocity_m_s(axis);
  const double v1 = std::clamp(v0 + wanted_m_s2 * dt_s, -v_max, v_max);
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
  limiting_ = !(CaughtUp(target, dt_s) && WithinLimits(target, dt_s));
  return flown_;
}

}  // namespace birotor
