// The setpoint a flight controller flies (channel SETPOINT,
// lcmtypes/setpoint_t.lcm) as a plain struct, and the reference the
// position law tracks from it. The controller daemon, the lock-step closed
// loop and the simulator's trajectory publisher all use this one type, so
// live and lock-step fly the same reference. No LCM, no Eigen here (the
// transport converts it).
#pragma once

#include <cstdint>
#include <limits>

namespace birotor {

// Field for field setpoint_t: world frame (x to the right, z up).
struct Setpoint {
  int64_t utime = 0;  // vehicle time the setpoint is meant for [us]
  int32_t seq = 0;    // publisher's counter, wraps
  double x_m = 0.0;   // position [m]
  double z_m = 0.0;
  // Feed-forward; NaN when not given (taken as 0).
  double x_dot_m_s = std::numeric_limits<double>::quiet_NaN();  // [m/s]
  double z_dot_m_s = std::numeric_limits<double>::quiet_NaN();
  double x_ddot_m_s2 = std::numeric_limits<double>::quiet_NaN();  // [m/s^2]
  double z_ddot_m_s2 = std::numeric_limits<double>::quiet_NaN();
};

// Conversions to and from the law's ReferencePoint: controller/reference_point.h.

}  // namespace birotor
