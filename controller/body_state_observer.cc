#include "controller/body_state_observer.h"

#include <algorithm>
#include <cmath>

#include "numerics/time_units.h"

namespace birotor {
namespace {

// Longest pose interval the correction gains are scaled for [s]: after a
// longer gap 2 w T would approach 1 and the correction overshoot.
constexpr double kMaxCorrectionIntervalS = 0.05;

}  // namespace

void BodyStateObserver::Initialize(const Eigen::Vector2d& position_m, double phi_rad) {
  state_ = BodyState();
  state_.position_m = position_m;
  state_.phi_rad = phi_rad;
}

void BodyStateObserver::Relocate(const Eigen::Vector2d& position_m, double phi_rad) {
  state_.position_m = position_m;
  state_.phi_rad = phi_rad;
}

void BodyStateObserver::Predict(double dt_s, const Eigen::Vector2d& accel_world_m_s2, double pitch_rate_rad_s) {
  state_.position_m += dt_s * state_.velocity_m_s + 0.5 * dt_s * dt_s * accel_world_m_s2;
  state_.velocity_m_s += dt_s * accel_world_m_s2;
  if (!std::isnan(pitch_rate_rad_s)) state_.phi_dot_rad_s = pitch_rate_rad_s;
  state_.phi_rad += dt_s * state_.phi_dot_rad_s;
}

void BodyStateObserver::CorrectPose(const Eigen::Vector2d& position_m, double phi_rad, double interval_s,
                                    bool gyro_in_use) {
  const double t = std::clamp(interval_s, 0.0, kMaxCorrectionIntervalS);
  const double w = params_.position_bandwidth_rad_s;
  const Eigen::Vector2d error = position_m - state_.position_m;
  state_.position_m += 2.0 * w * t * error;
  state_.velocity_m_s += w * w * t * error;
  const double wc = params_.attitude_crossover_rad_s;
  const double tilt_error = phi_rad - state_.phi_rad;
  // Without the gyro the tilt uses the same second-order form as position.
  state_.phi_rad += (gyro_in_use ? wc : 2.0 * wc) * t * tilt_error;
  if (!gyro_in_use) state_.phi_dot_rad_s += wc * wc * t * tilt_error;
}

Eigen::Vector2d WorldAcceleration(double phi_rad, double specific_force_x_m_s2, double specific_force_z_m_s2,
                                  double gravity_m_s2) {
  const double c = std::cos(phi_rad), s = std::sin(phi_rad);
  return Eigen::Vector2d(c * specific_force_x_m_s2 - s * specific_force_z_m_s2,
                         s * specific_force_x_m_s2 + c * specific_force_z_m_s2 - gravity_m_s2);
}

void BodyStateObserver::FuseHeldPose(bool gyro_in_use) {
  if (!pose_held_) return;
  const double interval_s = ElapsedSeconds(held_pose_.utime, last_fused_pose_utime_);
  CorrectPose(Eigen::Vector2d(held_pose_.x_m, held_pose_.z_m), held_pose_.phi_rad, interval_s, gyro_in_use);
  last_fused_pose_utime_ = held_pose_.utime;
  pose_held_ = false;
}

}  // namespace birotor
