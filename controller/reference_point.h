// A position reference for the flight controllers: where the body should be,
// how fast it should move and the acceleration that feeds forward.
#pragma once

#include <Eigen/Core>

namespace birotor {

// Reference position, velocity and acceleration, world frame [m, m/s, m/s^2].
struct ReferencePoint {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity_m_s = Eigen::Vector2d::Zero();
  Eigen::Vector2d acceleration_m_s2 = Eigen::Vector2d::Zero();
};

}  // namespace birotor
