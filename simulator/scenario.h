// A simulation scenario as plain data: vehicle, trajectory or bench profile,
// sensors, faults and controller gains. Defaults are the reference vehicle and
// sensors of shared/spec/reference-vehicle.md; params/scenario_yaml.h loads it.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "controller/controller_params.h"
#include "model/birotor_params.h"
#include "model/vehicle_description.h"

namespace birotor {

// One value per arm (or rotor) of the vehicle, entries [0, Scenario::arm_count)
// read from the file; the birotor uses entries 0 and 1.
using PerArm = std::array<double, kMaxArms>;
inline constexpr PerArm kEveryArmOne = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0};

// One quintic move (zero velocity and acceleration at both ends) from where
// the reference is at start_s to (x_m, z_m), world frame.
struct Waypoint {
  double start_s = 0.0;     // time the move starts [s]
  double duration_s = 1.0;  // time the move takes [s]
  double x_m = 0.0;
  double z_m = 0.0;
};

// Random quintic position steps for identification flights (flight_id).
struct RandomSteps {
  double interval_s = 1.5;       // a new step starts every interval [s]
  double max_step_m = 0.3;       // each axis moves by U[-max, max] per step [m]
  double move_duration_s = 1.0;  // duration of each quintic move [s]
  double max_excursion_m = 0.5;  // targets stay within +-this of the start, per axis [m]
};

struct TrajectoryParams {
  // "hold": hold the start position; "waypoints": the list below;
  // "random_steps": RandomSteps drawn from the scenario seed.
  std::string kind = "hold";
  std::vector<Waypoint> waypoints;
  RandomSteps random_steps;
};

// Open-loop rotor speed commands on the test stand: segments alternate between
// random steps (independent per rotor) and a linear chirp on every rotor
// (odd rotors in phase, even rotors in antiphase).
struct BenchProfile {
  double omega_low_rad_s = 300.0;    // lowest commanded speed [rad/s]
  double omega_high_rad_s = 1100.0;  // highest commanded speed [rad/s]
  double segment_s = 10.0;           // length of each steps/chirp segment [s]
  double step_hold_s = 0.5;          // time between random steps [s]
  double chirp_start_hz = 0.2;       // chirp frequency at the segment start [Hz]
  double chirp_end_hz = 8.0;         // chirp frequency at the segment end [Hz]
};

// One sensor: emitted every 1/rate_hz (an exact multiple of the step).
struct SensorRate {
  bool enabled = true;
  double rate_hz = 1000.0;
};

struct SensorParams {
  SensorRate strain{true, 1000.0};
  double strain_noise_rad = 2e-5;  // white noise on each deflection, one sigma
  // The gauges are read at t + e while the sample is stamped t: e ~ N(0,
  // stamp_jitter_s^2), drawn per sample (one instant for every arm), from its
  // own noise stream; 0: read exactly at the stamp [s]. The reading at t + e
  // is taken to first order, b(t) + e b_dot(t) (the arm mode's period,
  // 14 ms, is 280 times 50 us), on the deflection only (offset, drift and
  // pickup as at t).
  double strain_stamp_jitter_s = 0.0;
  SensorRate motor{true, 500.0};
  bool motor_telemetry = true;           // false: omega_meas is NaN throughout
  double motor_speed_noise_rad_s = 5.0;  // on omega_meas, one sigma
  SensorRate imu{true, 1000.0};
  double gyro_noise_rad_s = 0.005;
  double accel_noise_m_s2 = 0.05;
  SensorRate pose{true, 100.0};
  double pose_position_noise_m = 1e-3;
  double pose_angle_noise_rad = 2e-3;
  SensorRate loadcell{false, 1000.0};
  double loadcell_noise_n = 0.02;
  SensorRate truth{true, 1000.0};
};

// A step of rotor i's thrust efficiency s_i at time_s.
struct ThrustStep {
  double time_s = 0.0;
  int rotor = 1;       // 1 .. Scenario::arm_count
  double scale = 1.0;  // new s_i [1]
};

// A time window [start_s, start_s + duration_s); duration 0 means none.
struct TimeWindow {
  double start_s = 0.0;
  double duration_s = 0.0;
};

struct FaultParams {
  PerArm initial_thrust_scale = kEveryArmOne;  // s_i at t = 0 (density: 0.9)
  std::vector<ThrustStep> thrust_steps;
  TimeWindow strain_gap;                            // strain samples not emitted (seq advances)
  double strain_spike_probability = 0.0;            // per strain sample
  double strain_spike_sigmas = 50.0;                // spike size on one arm, in strain noise sigmas
  std::vector<double> strain_nan_times_s;           // sample at/after each time is NaN
  std::vector<double> strain_out_of_order_times_s;  // sample at/after each time swapped with the next
  TimeWindow motor_telemetry_gap;                   // omega_meas NaN, commands continue
};

// A real strain gauge (shared/spec/gauges.md):
//   b_meas_i(t) = s_i b_i(t) + o_i(t) + v_i(t) + n_i(t)
// with o_i(t) = offset_i + drift_i * (time spent inside drift_window) and the
// rotor-harmonic pickup v_i = a1_i sin(theta_i) + a2_i sin(2 theta_i + phase2_i),
// theta_i the angle of rotor i (integrated from its own speed). n_i is
// sensors.strain.noise_rad. Defaults: the ideal gauge of reference-vehicle.md.
struct GaugeParams {
  PerArm scale = kEveryArmOne;     // s_i [1]
  PerArm offset_rad{};             // o_i at power-up [rad]
  PerArm drift_rad_s{};            // do_i/dt inside drift_window [rad/s]
  TimeWindow drift_window;         // duration 0: no drift
  PerArm harmonic_1x_rad{};        // a1_i, pickup at the rotor speed [rad]
  PerArm harmonic_2x_rad{};        // a2_i, pickup at twice the rotor speed [rad]
  PerArm harmonic_2x_phase_rad{};  // phase2_i [rad]
  PerArm rotor_angle_rad{};        // theta_i at t = 0 [rad]
};

// The ground phase of a real flight (shared/spec/gauges.md): rest on the
// ground with the motors stopped, arm and spool up to idle, then the flight
// controller takes over (trajectory times count from then); lift-off happens
// when the thrust exceeds the weight. Optionally the flight ends with a
// vertical descent to the start height, motors stopped, and rest. The ground
// is a support under the body at the start height: it holds x, z and phi
// (level) while the vertical acceleration of the free body would be
// downwards; the arms still bend under their weight and the thrust.
struct GroundParams {
  bool enabled = false;             // false: the flight starts in hover (as the existing scenarios)
  double rest_s = 3.0;              // at rest with the motors stopped before arming [s]
  double spool_up_s = 1.0;          // command ramp from 0 to idle [s]
  double idle_rad_s = 300.0;        // rotor speed at idle [rad/s]
  bool land = false;                // end the flight with a landing
  double landing_duration_s = 3.0;  // quintic descent to the start height [s]
  double rest_after_s = 2.0;        // motors stopped on the ground at the end [s]
  // Time the flight controller takes over (trajectory time 0) [s].
  double FlightStartS() const { return enabled ? rest_s + spool_up_s : 0.0; }
};

// The ESCs' commander rule when the simulator runs external MOTOR_COMMANDs
// (Simulator::UseExternalCommands, controller/seq_stream_lock.h, issue 37):
// one seq stream at a plausible rate; after receiver time dt since the
// stream's last command, a seq step above 1 + command_max_rate_hz dt
// (1 + rate_margin) + seq_slack or a stamp advance above dt + stamp_slack_s
// is a second commander: a conflict (counted) until one has been silent for
// conflict_hold_s. follow_commander_in_conflict true: the ESCs keep running
// the locked commander's in-stream commands and refuse the other; false:
// both are refused (the last good command holds, then the command timeout
// spools the rotors down; a 1 s attack then drops the vehicle, measured in
// tests/evaluation/stream_takeover_test.cc).
struct EscParams {
  double command_max_rate_hz = 750.0;  // MOTOR_COMMAND: 500 Hz nominal [Hz]
  double rate_margin = 0.5;            // [1]
  double seq_slack = 3.0;              // [1]
  double stamp_slack_s = 0.05;         // [s]
  double conflict_hold_s = 0.1;        // [s]
  bool follow_commander_in_conflict = true;
};

struct Scenario {
  std::string file;  // where it was loaded from (messages only)
  std::string name = "hover";
  std::string mode = "flight";  // "flight" or "bench" (body clamped)
  // Entries of the per-arm lists (gauge:, faults.initial_thrust_scale) and
  // the rotors a fault may name: the vehicle's arm count (LoadScenario's
  // arm_count; 2, the birotor, unless --vehicle names a description).
  int arm_count = kBirotorArmCount;
  double duration_s = 20.0;
  uint64_t seed = 1;
  double step_s = 0.00025;                  // RK4 step; a whole number of microseconds
  double start_position_m[2] = {0.0, 0.0};  // x, z
  // The flown vehicle (the scenario's `vehicle:` section, birotor form); the
  // birotor simulator flies it through BirotorModelOf. --vehicle FILE flies a
  // description with N arms instead (services/birotor_sim_vehicle.h).
  VehicleDescription vehicle = BirotorDescription(BirotorParams());
  TrajectoryParams trajectory;
  BenchProfile bench;
  SensorParams sensors;
  GaugeParams gauge;
  GroundParams ground;
  FaultParams faults;
  ControllerParams controller;  // gains of the built-in autopilot
  EscParams esc;                // the ESCs' commander rule (external commands only)
};

}  // namespace birotor
