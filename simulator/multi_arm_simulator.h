// The simulation engine for any VehicleDescription (N = 2 .. 6 arms), every
// scenario kind of the birotor's simulator/simulator.h from the same scenario
// file and the same pieces: integrates the plant of model/multi_arm_plant.h
// with RK4 at the scenario's fixed step; flies it with MultiArmAutopilot (or an
// external controller's commands, UseExternalCommands)
// along the trajectory (flight), from the ground (the ground phase of
// ground_phase.h: rest, spool-up, lift-off, landing), or runs the bench
// profile of bench_profile.h with the body clamped (bench); with the rotor
// turbulence and thrust-efficiency steps on any rotor; and emits at exact
// multiples of the step the real gauges of gauge_model.h on the arms that
// have one (with the strain faults of strain_faults.h), motor telemetry
// (with its gap), IMU, POSE, a load cell per rotor and TRUTH. Deterministic
// from the scenario seed. docs/multi-arm-model.md, "Simulator".
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "model/multi_arm_linearization.h"
#include "model/multi_arm_plant.h"
#include "model/vehicle_description.h"
#include "samples/sample_sink.h"
#include "simulator/bench_profile.h"
#include "simulator/fault_event.h"
#include "simulator/ground_phase.h"
#include "simulator/multi_arm_autopilot.h"
#include "simulator/noise.h"
#include "simulator/scenario.h"
#include "simulator/simulator.h"
#include "simulator/strain_faults.h"
#include "simulator/trajectory.h"

namespace birotor {

// Every reason the scenario cannot run on the vehicle, one sentence each
// naming the key; empty when it can: the description's PlausibilityProblems,
// a scenario loaded for another arm count (Scenario::arm_count: its per-arm
// lists), and a thrust step on a rotor outside [1, N].
std::vector<std::string> MultiArmScenarioProblems(const VehicleDescription& vehicle, const Scenario& scenario);

class MultiArmSimulator {
 public:
  // Throws std::invalid_argument with MultiArmScenarioProblems joined by
  // "; " when they are not empty. The flown vehicle is the description
  // changed as the scenario's vehicle: section differs from the reference
  // birotor (FlownVehicle, simulator/flown_vehicle.h: the description
  // itself when the section is the reference's); every other section is
  // used as the birotor's simulator uses it; the true gauges are the gauge:
  // section (the description's gauge_scale and gauge_offset_rad are what an
  // estimator believes). vehicle() is the flown vehicle.
  MultiArmSimulator(const VehicleDescription& vehicle, const Scenario& scenario);

  // Emits the samples due at the current time to sink (may be null: none),
  // then advances one step (commands at the control rate, thrust steps,
  // ground contact, turbulence, RK4). Returns false (and does nothing) once
  // the duration is reached. Does not allocate except to record fault
  // events. Sensors and noise: scenario.sensors (rates, sigmas,
  // motor_telemetry), each from the birotor's noise stream of the seed.
  bool Step(SampleSink* sink = nullptr);
  void Run(SampleSink* sink = nullptr);

  // In flight the rotor commands come from OfferRotorCommands (an external
  // controller, as Simulator::UseExternalCommands for the birotor) instead of
  // the autopilot; the ground phase and the bench keep their own. The last
  // offer holds (before the first: the start state's rotor speeds). Call
  // before the first step; without it the autopilot flies (unchanged).
  void UseExternalCommands();
  // Speeds [rad/s] of rotors 1 .. N for the step about to be taken and on
  // (the plant clamps each to [0, omega_max]).
  void OfferRotorCommands(const std::array<double, kMaxArms>& omega_cmd_rad_s);
  bool external_commands() const { return external_commands_; }
  // The scenario's position reference at simulated time t_s (trajectory
  // time from the end of the ground phase), as the autopilot flies it.
  ReferencePoint ReferenceAt(double t_s) const { return trajectory_.At(t_s - scenario_.ground.FlightStartS()); }

  bool done() const { return step_index_ >= total_steps_; }
  double time_s() const { return static_cast<double>(step_index_) * scenario_.step_s; }
  // Simulated time of the current step plus the offset [us].
  int64_t utime() const { return utime_offset_us_ + step_index_ * step_us_; }
  // Added to every utime (for --wall-clock); call before the first step.
  void set_utime_offset_us(int64_t offset_us) { utime_offset_us_ = offset_us; }

  const VehicleDescription& vehicle() const { return vehicle_; }  // the flown one
  const Scenario& scenario() const { return scenario_; }
  const MultiArmPlantState& state() const { return state_; }
  // Commands and mu_i = s_i (1 + eta_i) of the step about to be taken.
  const MultiArmPlantInput& input() const { return input_; }
  const MultiArmHover& hover() const { return hover_; }
  const ReferencePoint& reference() const { return reference_; }
  const MultiArmRotorCommand& command() const { return command_; }
  MultiArmControlMode mode() const { return autopilot_.mode(); }
  // Ground phase: true while the ground supports the body; the first
  // lift-off [us] (with the offset), -1 before it or without the phase.
  bool on_ground() const { return ground_.on_ground(); }
  int64_t liftoff_utime() const { return ground_.liftoff_utime(); }
  // f_i = mu_i c_T,i omega_i of the current state [N] (arm 0-based).
  double TrueForce(int arm) const;
  // Thrust steps that took effect and the sensor faults injected (rotor 1-based).
  const std::vector<FaultEvent>& fault_events() const { return fault_events_; }
  // Samples emitted per channel (a strain sample lost in a gap is not counted).
  const ChannelCounts& emitted() const { return emitted_; }

 private:
  struct ScheduledStep {
    int64_t step = 0;
    int rotor = 0;  // 0-based
    double scale = 1.0;
  };

  // The start state: the exact hover at the start position (flight), at
  // rest on the support with the motors stopped (ground phase), or the
  // clamped body with every arm at its static deflection under the first
  // bench command (bench).
  void SetInitialState();
  // Rotor speed commands at t_s: the bench profile, the ground phase's, or
  // the autopilot's on the flight reference.
  void UpdateCommand(double t_s);
  MultiArmPlantState Derivative(const MultiArmPlantState& x) const;
  // After the step: rotor angles and touchdown.
  void AfterStep(const std::array<double, kMaxArms>& omega_before_rad_s);

  void EmitStrain(SampleSink* sink);
  void EmitMotor(SampleSink* sink);
  void EmitImu(const MultiArmPlantState& derivative, SampleSink* sink);
  void EmitPose(SampleSink* sink);
  void EmitLoadCell(SampleSink* sink);
  void EmitTruth(SampleSink* sink);
  // Steps between two samples of a sensor; 0: off.
  int64_t SensorEvery(const SensorRate& rate) const;

  VehicleDescription vehicle_;
  Scenario scenario_;
  bool clamped_body_;  // mode bench
  int64_t step_us_;
  int64_t total_steps_;
  int64_t control_every_steps_;
  int64_t step_index_ = 0;
  int64_t utime_offset_us_ = 0;

  MultiArmHover hover_;
  Trajectory trajectory_;
  MultiArmAutopilot autopilot_;
  BenchCommander bench_;
  GroundPhase ground_;
  ReferencePoint reference_;
  MultiArmRotorCommand command_;
  bool external_commands_ = false;                       // UseExternalCommands
  bool flying_external_ = false;                         // in flight on the external commands
  std::array<double, kMaxArms> external_omega_rad_s_{};  // the newest offer [rad/s]

  MultiArmPlantState state_;
  MultiArmPlantInput input_;
  std::array<double, kMaxArms> efficiency_{};       // s_i
  std::array<double, kMaxArms> rotor_angle_rad_{};  // theta_i for the harmonic pickup, in [0, 2 pi)
  GaussianSource turbulence_noise_;
  std::vector<GaussMarkov> turbulence_;  // eta_i, one per rotor
  std::vector<ScheduledStep> thrust_steps_;
  size_t next_thrust_step_ = 0;
  std::vector<FaultEvent> fault_events_;

  int64_t strain_every_ = 0, motor_every_ = 0, imu_every_ = 0, pose_every_ = 0, loadcell_every_ = 0, truth_every_ = 0;
  GaussianSource strain_noise_, strain_jitter_noise_, motor_noise_, imu_noise_, pose_noise_, loadcell_noise_,
      fault_noise_;
  StrainFaultInjector<MultiArmStrainSample> strain_faults_;
  int32_t strain_seq_ = 0, motor_seq_ = 0, imu_seq_ = 0, pose_seq_ = 0, loadcell_seq_ = 0;
  ChannelCounts emitted_;
};

}  // namespace birotor
