// The body-state observer: the accelerometer's specific force rotated to the
// world, and convergence of the POSE + IMU observer on a known motion.
#include "controller/body_state_observer.h"

#include <gtest/gtest.h>

#include <cmath>

namespace birotor {
namespace {

constexpr double kG = 9.81;

TEST(WorldAccelerationTest, LevelHoverIsZeroAndTiltedThrustPushesSideways) {
  EXPECT_NEAR(WorldAcceleration(0.0, 0.0, kG, kG).norm(), 0.0, 1e-15);
  // Thrust along body z that holds the weight at tilt phi: a = (-g tan phi, 0)
  // (phi > 0 turns body x towards +z, so body z leans towards -x).
  const double phi = 0.1;
  const Eigen::Vector2d a = WorldAcceleration(phi, 0.0, kG / std::cos(phi), kG);
  EXPECT_NEAR(a.x(), -kG * std::tan(phi), 1e-12);
  EXPECT_NEAR(a.y(), 0.0, 1e-12);
}

TEST(BodyStateObserverTest, ConvergesOnAConstantVelocityFromPoseAlone) {
  BodyStateObserver observer{ObserverParams()};
  observer.Initialize(Eigen::Vector2d::Zero(), 0.0);
  // x = 0.5 t, z = 0, level; POSE at 100 Hz, prediction at 500 Hz.
  for (int k = 1; k <= 1500; ++k) {
    const double t = k * 0.002;
    observer.Predict(0.002, Eigen::Vector2d::Zero(), 0.0);
    if (k % 5 == 0) observer.CorrectPose(Eigen::Vector2d(0.5 * t, 0.0), 0.0, 0.01, true);
  }
  // Type-2 observer: no steady error on a ramp; w = 10 rad/s -> e^-30 after 3 s.
  EXPECT_NEAR(observer.state().velocity_m_s.x(), 0.5, 1e-6);
  EXPECT_NEAR(observer.state().position_m.x(), 0.5 * 3.0, 1e-6);
  EXPECT_NEAR(observer.state().position_m.y(), 0.0, 1e-12);
}

TEST(BodyStateObserverTest, GyroRateIsUsedAndTiltFollowsPose) {
  BodyStateObserver observer{ObserverParams()};
  observer.Initialize(Eigen::Vector2d::Zero(), 0.0);
  observer.Predict(0.002, Eigen::Vector2d::Zero(), 0.25);
  EXPECT_DOUBLE_EQ(observer.state().phi_dot_rad_s, 0.25);
  EXPECT_DOUBLE_EQ(observer.state().phi_rad, 0.0005);
  // Complementary filter: one POSE pulls phi by w_c T of the error.
  observer.CorrectPose(Eigen::Vector2d::Zero(), 0.1005, 0.01, true);
  EXPECT_NEAR(observer.state().phi_rad, 0.0005 + 5.0 * 0.01 * 0.1, 1e-12);
}

}  // namespace
}  // namespace birotor
