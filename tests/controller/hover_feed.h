// A scripted vehicle for the supervised controller's tests
// (vehicle_controller_test.cc, degraded_flight_test.cc): POSE, IMU and FORCE
// of a level vehicle at x = 0 that climbs or sinks at a set speed, fed in
// 1 ms steps, one 500 Hz control period at a time.
#pragma once

#include <cmath>
#include <cstdint>

#include "controller/vehicle_controller.h"
#include "model/equilibrium.h"

namespace birotor {

inline constexpr int64_t kPeriodUs = 2000;  // 500 Hz (ControllerParams::rate_hz)

inline double HoverForce(const BirotorParams& p) {
  const Equilibrium e = SolveHoverEquilibrium(p);
  return 0.5 * (e.force_n[0] + e.force_n[1]);
}

// A vehicle at rest at the origin, level, seen by every sensor; FORCE
// reports the hover force on both rotors and thrust scales (1, scale2) with
// the given status. climb_m_s moves it up (down if negative) at that
// constant speed.
class HoverFeed {
 public:
  // A controller of config that has seen the first POSE (at the origin, t = 0).
  explicit HoverFeed(const ControllerConfig& config)
      : controller_(config), hover_force_n_(HoverForce(BirotorModelOf(config.vehicle))) {
    controller_.OnPose(PoseSample{0, pose_seq_++, 0.0, 0.0, 0.0}, 0);
  }
  bool send_pose = true;
  bool send_force = true;
  int32_t force_status = kStatusValid;
  double scale2 = 1.0;
  double climb_m_s = 0.0;

  // Feeds the samples of (now - period, now] and runs one control period.
  MotorCommand Period() {
    for (int64_t t = now_us_ + 1000; t <= now_us_ + kPeriodUs; t += 1000) {
      z_m_ += 1e-3 * climb_m_s;
      controller_.OnImu(ImuSample{t, imu_seq_++, 0.0, 0.0, 9.81}, t);
      if (send_force) {
        ForceEstimate force;
        force.utime = t;
        force.seq = force_seq_;
        force.force_n[0] = force.force_n[1] = hover_force_n_;
        force.force_std_n[0] = force.force_std_n[1] = 0.01 * hover_force_n_;
        force.thrust_scale[1] = scale2;
        force.status = force_status;
        controller_.OnForce(force, t);
      }
      ++force_seq_;
      if (send_pose && t % 10000 == 0) controller_.OnPose(PoseSample{t, pose_seq_++, 0.0, z_m_, 0.0}, t);
    }
    now_us_ += kPeriodUs;
    return controller_.Update(now_us_);
  }
  // n periods; returns the last command.
  MotorCommand Run(int periods) {
    MotorCommand c;
    for (int k = 0; k < periods; ++k) c = Period();
    return c;
  }
  // 2 s of hover: airborne (airborne_s 0.05 s) and the baseline settled
  // (baseline_tau_s 1 s), in force feedback when asked for.
  MotorCommand Settle() { return Run(1000); }
  // The vehicle is found dz_m higher than it was (the POSE that follows says
  // so; the IMU saw nothing): an observer that has drifted by -dz_m.
  void Teleport(double dz_m) { z_m_ += dz_m; }
  int64_t now_us() const { return now_us_; }
  double z_m() const { return z_m_; }
  VehicleController& controller() { return controller_; }

 private:
  VehicleController controller_;
  double hover_force_n_;
  int64_t now_us_ = 0;
  double z_m_ = 0.0;
  int32_t imu_seq_ = 0, pose_seq_ = 0, force_seq_ = 0;
};

}  // namespace birotor
