// A position reference for the flight controllers: where the body should be,
// how fast it should move and the acceleration that feeds forward.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "samples/setpoint.h"

namespace birotor {

// Reference position, velocity and acceleration, world frame [m, m/s, m/s^2].
struct ReferencePoint {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity_m_s = Eigen::Vector2d::Zero();
  Eigen::Vector2d acceleration_m_s2 = Eigen::Vector2d::Zero();
};

// The setpoint of a reference at utime (every feed-forward given).
Setpoint SetpointFromReference(const ReferencePoint& reference, int64_t utime, int32_t seq);

// The reference of a setpoint extrapolated by dt_s [s] (0: as it is):
//   p = p0 + v dt + a dt^2 / 2,  v = v0 + a dt,  a = a0
// with a feed-forward that is not given (NaN) taken as 0 (controller/setpoint.cc).
ReferencePoint ReferenceFromSetpoint(const Setpoint& setpoint, double dt_s = 0.0);

// The controlled descent's reference (both controllers; POSE lost or hover
// infeasible): where the observer puts the body, so the position error is
// held at zero, sinking at descent_rate_m_s [m/s], no feed-forward.
inline ReferencePoint DescentReference(const Eigen::Vector2d& position_m, double descent_rate_m_s) {
  ReferencePoint target;
  target.position_m = position_m;
  target.velocity_m_s = Eigen::Vector2d(0.0, -descent_rate_m_s);
  return target;
}

}  // namespace birotor
