// The ground phase of scenario.h's GroundParams as a schedule and a contact
// state, one copy for the birotor and the N-arm simulator: at rest with the
// motors stopped, the spool-up ramp to idle, the flight (the trajectory from
// FlightStartS on, the landing's vertical descent at its end), the motors
// stopped after it; lift-off when the free body would accelerate upwards,
// touchdown when it comes back to the support's height. The plant on the
// support (body held level and still, arms free) is the simulator's.
#pragma once

#include <cstdint>

#include "controller/reference_point.h"
#include "simulator/scenario.h"
#include "simulator/trajectory.h"

namespace birotor {

class GroundPhase {
 public:
  // The support is at the scenario's start height; the body starts on it
  // when the phase is enabled.
  explicit GroundPhase(const Scenario& scenario);

  bool enabled() const { return params_.enabled; }
  // True while the support holds the body.
  bool on_ground() const { return on_ground_; }
  double support_z_m() const { return support_z_m_; }
  // Time of the first lift-off [us]; -1 before it or without the phase.
  int64_t liftoff_utime() const { return liftoff_utime_; }

  // The speed every rotor is commanded at t_s [rad/s] while the phase, not
  // the flight controller, commands: 0 at rest and once disarmed after the
  // landing, idle_rad_s (t - rest_s) / spool_up_s during the spool-up.
  // False while the flight controller commands.
  bool PhaseCommand(double t_s, double* omega_cmd_rad_s) const;

  // The flight controller's reference at t_s: the trajectory at t_s -
  // FlightStartS, or once the landing has started the quintic descent from
  // where the reference was to the support's height.
  ReferencePoint FlightReference(double t_s, const Trajectory& trajectory);

  // Before a step on the support: the body leaves it when the free body's
  // vertical acceleration free_z_ddot() [m/s^2] is upwards (the support only
  // pushes); evaluated only while on the ground.
  template <class FreeZAcceleration>
  void UpdateLiftoff(int64_t now_us, FreeZAcceleration&& free_z_ddot) {
    if (!on_ground_ || !(free_z_ddot() > 0.0)) return;
    on_ground_ = false;
    if (liftoff_utime_ < 0) liftoff_utime_ = now_us;
  }

  // After a step in the air: true when the body reached the support (z_m at
  // or below its height), which the caller then puts on it, level and still
  // (an inelastic contact; the arms keep their state).
  bool Touchdown(double z_m);

 private:
  GroundParams params_;
  bool on_ground_ = false;
  int64_t liftoff_utime_ = -1;
  double support_z_m_ = 0.0;   // height of the support [m]
  double land_start_s_ = 0.0;  // descent starts [s] (land only)
  double disarm_s_ = 0.0;      // motors stopped [s] (land only)
  QuinticMove landing_;        // descent, in simulated time
  bool landing_planned_ = false;
};

}  // namespace birotor
