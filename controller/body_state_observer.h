// The controller service's estimate of the rigid-body state from what a real
// vehicle has: POSE (motion capture, ~100 Hz) and the IMU (~1 kHz). It never
// sees TRUTH. Per world axis a critically damped second-order observer
//   p' = v + 2 w (p_meas - p),   v' = a + w^2 (p_meas - p)
// with a the accelerometer's specific force rotated to the world frame minus
// gravity; the tilt is a complementary filter: the gyro integrated, pulled
// towards POSE's phi at the crossover frequency. Fixed size, no allocation.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "controller/controller_params.h"
#include "controller/position_attitude_law.h"
#include "samples/samples.h"

namespace birotor {

class BodyStateObserver {
 public:
  explicit BodyStateObserver(const ObserverParams& params) : params_(params) {}

  // Starts at a pose, at rest.
  void Initialize(const Eigen::Vector2d& position_m, double phi_rad);
  // Moves the estimate onto a pose, keeping the velocity and pitch rate (the
  // IMU's: a POSE re-acquisition after the position drifted).
  void Relocate(const Eigen::Vector2d& position_m, double phi_rad);

  // Propagates over dt_s [s] with the world acceleration [m/s^2]. With a
  // measured pitch rate (gyro) the rate is that measurement; without it
  // (pitch_rate_rad_s NaN) the rate is held and corrected by POSE instead.
  void Predict(double dt_s, const Eigen::Vector2d& accel_world_m_s2, double pitch_rate_rad_s);

  // Corrects with one POSE sample taken interval_s [s] after the previous one
  // (the gains scale with it; clamped to 50 ms so a gap cannot overshoot).
  void CorrectPose(const Eigen::Vector2d& position_m, double phi_rad, double interval_s, bool gyro_in_use);

  // The newest POSE, held until the next control period fuses it
  // (FuseHeldPose); a newer one replaces it.
  void HoldPose(const PoseSample& sample) {
    held_pose_ = sample;
    pose_held_ = true;
  }
  // A POSE used at once (the first, a reset, a re-acquisition): the next
  // interval counts from its stamp; a held one is dropped.
  void PoseUsedAt(int64_t utime) {
    last_fused_pose_utime_ = utime;
    pose_held_ = false;
  }
  // Corrects with the held POSE, if any, over the time since the last one
  // fused or used (CorrectPose).
  void FuseHeldPose(bool gyro_in_use);

  const BodyState& state() const { return state_; }

 private:
  ObserverParams params_;
  BodyState state_;
  PoseSample held_pose_;
  bool pose_held_ = false;
  int64_t last_fused_pose_utime_ = -1;  // [us]
};

// World acceleration from the accelerometer's specific force in body axes:
// a = R(phi) f_b - [0, g], R(phi) = [cos -sin; sin cos] (phi turns body x
// towards world +z) [m/s^2].
Eigen::Vector2d WorldAcceleration(double phi_rad, double specific_force_x_m_s2, double specific_force_z_m_s2,
                                  double gravity_m_s2);

}  // namespace birotor
