// The reference the controller flies, shaped (issue 37): it follows the
// target (the newest accepted setpoint, extrapolated, or a hold point)
// exactly while the target moves within the speed and acceleration limits,
// and otherwise approaches it as a second-order reference model with rate
// and acceleration limits (per world axis |v| <= max_speed, |a| <=
// max_accel) until it has caught up.
// A setpoint far away is approached at the limits, not refused.
// No allocation, no throw.
#pragma once

#include <cstdint>

#include "controller/reference_point.h"

namespace birotor {

// Limits and tolerances (SetpointParams max_speed_m_s, max_accel_m_s2,
// shaping_position_tolerance_m, shaping_velocity_tolerance_m_s).
struct ShaperLimits {
  double max_speed_m_s = 1.4;            // per axis [m/s]
  double max_accel_m_s2 = 2.6;           // per axis [m/s^2]
  double position_tolerance_m = 0.001;   // target step beyond max_speed dt still followed exactly [m]
  double velocity_tolerance_m_s = 0.01;  // velocity step beyond max_accel dt still followed exactly [m/s]
  double bandwidth_rad_s = 4.0;          // natural frequency of the shaping reference model [rad/s]
};

class ReferenceShaper {
 public:
  explicit ReferenceShaper(const ShaperLimits& limits) : limits_(limits) {}

  // Starts (or restarts) at reference, passing the target through.
  void Reset(const ReferencePoint& reference);
  // The reference flown at this period, dt_s [s] after the previous call,
  // towards target.
  ReferencePoint Step(const ReferencePoint& target, double dt_s);

  bool limiting() const { return limiting_; }                   // the last Step was shaped
  int64_t limited_periods() const { return limited_periods_; }  // shaped Steps since start
  const ReferencePoint& flown() const { return flown_; }

 private:
  // True when the target moved from the flown reference as a reference
  // within the limits can (plus the tolerances) over dt_s.
  bool WithinLimits(const ReferencePoint& target, double dt_s) const;
  // One limiter step of one axis towards the target.
  void LimitAxis(int axis, const ReferencePoint& target, double dt_s);
  bool CaughtUp(const ReferencePoint& target, double dt_s) const;

  ShaperLimits limits_;
  ReferencePoint flown_;
  bool limiting_ = false;
  int64_t limited_periods_ = 0;
};

}  // namespace birotor
