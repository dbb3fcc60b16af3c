#include "evaluation/control_cases.h"

#include <cmath>
#include <string>

namespace birotor {
namespace {

// Issue 34: a hover-infeasible loss during the aggressive manoeuvre. Take off
// to 0.3 m (the force-feedback baseline settles in the hover), at 3 s the
// aggressive quintic move by (+1, +1) m in 2 s; rotor `rotor` drops to
// `scale` mid-climb (flight time 4 s = 6 s from the start, at about 0.8 m,
// climbing and moving at 0.94 m/s each way).
ControlCase AggressiveLoss(const char* name, int rotor, double scale) {
  return ControlCase{name,
                     "aggressive",
                     {"scenario.duration_s=9", "ground.enabled=true", "ground.rest_s=1.0",
                      "trajectory.waypoints=[{start_s: 0.0, duration_s: 1.5, x_m: 0.0, z_m: 0.3}, "
                      "{start_s: 3.0, duration_s: 2.0, x_m: 1.0, z_m: 1.3}]",
                      "faults.thrust_steps=[{time_s: 6.0, rotor: " + std::to_string(rotor) +
                          ", scale: " + std::to_string(scale) + "}]"},
                     "aggressive move (+1, +1) m in 2 s from a 0.3 m hover, rotor " + std::to_string(rotor) +
                         " loses " + std::to_string(static_cast<int>(std::lround(100 * (1 - scale)))) + " % mid-climb"};
}

// Issue 36 item 5: a payload (body 4.0 -> 4.6 kg, +15 %) and rotor 1
// dropping to `scale` at 5 s in the hover (thrust_loss_severe's timing).
ControlCase PayloadLoss(const char* name, double scale) {
  return ControlCase{name,
                     "thrust_loss_severe",
                     {"scenario.duration_s=10", "vehicle.body_mass_kg=4.6",
                      "faults.thrust_steps=[{time_s: 5.0, rotor: 1, scale: " + std::to_string(scale) + "}]"},
                     "body mass +15 % (payload), rotor 1 loses " +
                         std::to_string(static_cast<int>(std::lround(100 * (1 - scale)))) + " % at 5 s"};
}

}  // namespace

const std::vector<ControlCase>& ControlCases() {
  // Durations are cut to what the figure needs (the fault plus its 3 s window).
  static const std::vector<ControlCase> cases = {
      {"hover", "hover", {"scenario.duration_s=10"}, "reference hover"},
      {"gentle", "gentle", {}, "reference gentle manoeuvres"},
      {"aggressive", "aggressive", {}, "reference aggressive manoeuvre"},
      {"aggressive_limit",
       "aggressive",
       {"trajectory.waypoints=[{start_s: 0.0, duration_s: 0.76, x_m: 1.0, z_m: 1.0}]"},
       "aggressive in 0.76 s: 10 m/s^2 per axis, the fastest feed-forward SETPOINT accepts "
       "(max_feed_forward_accel_m_s2), flown unshaped (shaping opened to 3 m/s, 10.5 m/s^2)",
       3.0,
       10.5},
      {"thrust_loss", "thrust_loss", {"scenario.duration_s=10"}, "rotor 2 loses 25 % at 5 s"},
      {"stiffness_-20",
       "hover",
       {"scenario.duration_s=10", "vehicle.arm_stiffness_n_m_rad=2102.4"},
       "arm stiffness -20 % (plant only), hover"},
      {"mass_-15", "hover", {"scenario.duration_s=10", "vehicle.body_mass_kg=3.4"}, "body mass -15 %, hover"},
      {"motor_tau_+70", "gentle", {"vehicle.motor_time_constant_s=0.0595"}, "motor time constant +70 %, gentle"},
      {"motor_tau_x3",
       "hover",
       {"scenario.duration_s=10", "vehicle.motor_time_constant_s=0.105"},
       "motor time constant 3x the file's (0.105 s), hover (without the thrust lead lost from 1.9x)"},
      {"motor_tau_+70_loss_50",
       "thrust_loss_severe",
       {"scenario.duration_s=10", "vehicle.motor_time_constant_s=0.0595",
        "faults.thrust_steps=[{time_s: 5.0, rotor: 2, scale: 0.5}]"},
       "motor time constant +70 %, rotor 2 loses 50 % at 5 s (FORCE's thrust scales swing with the lag)"},
      {"gauge_scale_0.7",
       "hover",
       {"scenario.duration_s=10", "gauge.scale=[0.7, 1.0]"},
       "gauge scale 0.7 on arm 1, hover"},
      {"untared_loss",
       "thrust_loss",
       {"scenario.duration_s=10", "gauge.offset_rad=[5.0e-4, 0.0]"},
       "untared offset 5e-4 rad on arm 1, rotor 2 loses 25 % at 5 s"},
      {"ground_start", "gauge_offset", {"scenario.duration_s=12"}, "ground start with gauge offsets (gauge_offset)"},
      {"severe_gap",
       "thrust_loss_severe",
       {"scenario.duration_s=10", "faults.strain_gap={start_s: 5.0, duration_s: 0.5}"},
       "rotor 2 loses 40 % at 5 s with a 0.5 s strain gap from the fault"},
      {"imu_noise",
       "hover",
       {"scenario.duration_s=10", "sensors.imu.accel_noise_m_s2=1.0"},
       "IMU accelerometer noise 1 m/s^2, hover"},
      {"loss_40", "thrust_loss_severe", {"scenario.duration_s=10"}, "rotor 2 loses 40 % at 5 s (issue 21)"},
      {"loss_60",
       "thrust_loss_severe",
       {"scenario.duration_s=10", "faults.thrust_steps=[{time_s: 5.0, rotor: 2, scale: 0.4}]"},
       "rotor 2 loses 60 % at 5 s (issue 21)"},
      {"loss_70",
       "thrust_loss",
       {"scenario.duration_s=12", "ground.enabled=true", "ground.rest_s=1.0", "trajectory.kind=waypoints",
        "trajectory.waypoints=[{start_s: 0.0, duration_s: 2.0, x_m: 0.0, z_m: 0.4}]",
        "faults.thrust_steps=[{time_s: 6.0, rotor: 2, scale: 0.3}]"},
       "take off to 0.4 m, rotor 2 loses 70 % at 6 s (hover impossible: level descent)"},
      AggressiveLoss("agg_loss70_r1", 1, 0.3),
      AggressiveLoss("agg_loss70_r2", 2, 0.3),
      AggressiveLoss("agg_loss80_r1", 1, 0.2),
      AggressiveLoss("agg_loss80_r2", 2, 0.2),
      {"loss_80",
       "thrust_loss",
       {"scenario.duration_s=12", "ground.enabled=true", "ground.rest_s=1.0", "trajectory.kind=waypoints",
        "trajectory.waypoints=[{start_s: 0.0, duration_s: 2.0, x_m: 0.0, z_m: 0.4}]",
        "faults.thrust_steps=[{time_s: 6.0, rotor: 2, scale: 0.2}]"},
       "take off to 0.4 m, rotor 2 loses 80 % at 6 s (FORCE at its plausibility floor: level descent)"},
      // Issue 36 item 5: a changed vehicle the estimator can read (c_T 4.6e-5
      // x 0.85 = 3.91e-5; body 4.0 x 1.15 = 4.6 kg; tip mass 0.28812 x 1.2).
      {"ct_-15",
       "hover",
       {"scenario.duration_s=10", "vehicle.thrust_coeff_n_s2_rad2=3.91e-5"},
       "thrust coefficient c_T -15 % (plant only), hover"},
      {"density_0.85",
       "hover",
       {"scenario.duration_s=10", "faults.initial_thrust_scale=[0.85, 0.85]"},
       "air 15 % thinner (both rotors at 0.85 of the map throughout), hover"},
      PayloadLoss("payload_+15_loss_40", 0.6),
      PayloadLoss("payload_+15_loss_60", 0.4),
      {"all_different",
       "mismatch_all",
       {"scenario.duration_s=10"},
       "mismatch_all vehicle: k +20 %, m_p +20 %, m +15 %, gauge scale 0.7 on arm 1, c_T +20 %, tau_m +30 %, "
       "gentle"},
      {"tip_mass_+20",
       "hover",
       {"scenario.duration_s=10", "vehicle.tip_mass_kg=0.345744"},
       "tip mass +20 % (plant only), hover"},
      {"turbulence_0.05",
       "hover",
       {"scenario.duration_s=10", "vehicle.turbulence_std=0.05"},
       "thrust turbulence 0.05 (5x the default), hover"},
  };
  return cases;
}

ControllerConfig ControllerForCase(const ControlCase& c, ControllerConfig base) {
  if (c.reference_max_speed_m_s > 0) base.setpoint.max_speed_m_s = c.reference_max_speed_m_s;
  if (c.reference_max_accel_m_s2 > 0) base.setpoint.max_accel_m_s2 = c.reference_max_accel_m_s2;
  return base;
}

const ControlCase* FindControlCase(const std::string& name) {
  for (const ControlCase& c : ControlCases()) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

}  // namespace birotor
