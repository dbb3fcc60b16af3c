// The simulation engine for any VehicleDescription (N = 2 .. 6 arms):
// integrates the plant of model/multi_arm_plant.h with RK4 at the scenario's
// fixed step, flies it with MultiArmAutopilot along the scenario's trajectory,
// with the birotor simulator's rotor turbulence and thrust-efficiency steps on
// any rotor, and emits the ideal sensors (gauges plus white noise on the arms
// that have one, motor telemetry, IMU, POSE) and TRUTH at exact multiples of
// the step. Deterministic from the scenario seed. What it does not model yet
// (real-gauge effects, sensor faults, the ground phase, the bench):
// docs/multi-arm-model.md, "Simulator".
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "model/multi_arm_linearization.h"
#include "model/multi_arm_plant.h"
#include "model/vehicle_description.h"
#include "samples/sample_sink.h"
#include "simulator/multi_arm_autopilot.h"
#include "simulator/noise.h"
#include "simulator/scenario.h"
#include "simulator/simulator.h"
#include "simulator/trajectory.h"

namespace birotor {

// Every reason the scenario cannot run on the vehicle, one sentence each
// naming the key; empty when it can: the description's PlausibilityProblems,
// mode "bench" and the ground phase (not modelled yet), a thrust step on a
// rotor outside [1, N], and for N != 2 unequal faults.initial_thrust_scale
// entries (the file holds two; N rotors take them only when they agree, as
// the air's density does).
std::vector<std::string> MultiArmScenarioProblems(const VehicleDescription& vehicle, const Scenario& scenario);

class MultiArmSimulator {
 public:
  // Throws std::invalid_argument with MultiArmScenarioProblems joined by
  // "; " when they are not empty. The scenario's vehicle: section is not
  // used (the description is the vehicle); its trajectory, seed, step,
  // duration, start position, thrust faults and controller gains are.
  MultiArmSimulator(const VehicleDescription& vehicle, const Scenario& scenario);

  // Emits the samples due at the current time to sink (may be null: none),
  // then advances one step (control at its rate, thrust steps, turbulence,
  // RK4). Returns false (and does nothing) once the duration is reached.
  // Does not allocate except to record fault events. Sensors and noise:
  // scenario.sensors (rates, sigmas, motor_telemetry), the birotor's; its
  // strain, motor, IMU and POSE noise streams of the seed.
  bool Step(SampleSink* sink = nullptr);
  void Run(SampleSink* sink = nullptr);

  bool done() const { return step_index_ >= total_steps_; }
  double time_s() const { return static_cast<double>(step_index_) * scenario_.step_s; }
  int64_t utime() const { return step_index_ * step_us_; }

  const VehicleDescription& vehicle() const { return vehicle_; }
  const Scenario& scenario() const { return scenario_; }
  const MultiArmPlantState& state() const { return state_; }
  // Commands and mu_i = s_i (1 + eta_i) of the step about to be taken.
  const MultiArmPlantInput& input() const { return input_; }
  const MultiArmHover& hover() const { return hover_; }
  const ReferencePoint& reference() const { return reference_; }
  const MultiArmRotorCommand& command() const { return command_; }
  MultiArmControlMode mode() const { return autopilot_.mode(); }
  // f_i = mu_i c_T,i omega_i of the current state [N] (arm 0-based).
  double TrueForce(int arm) const;
  // Thrust steps that took effect (kind kThrustStep, rotor 1-based).
  const std::vector<FaultEvent>& fault_events() const { return fault_events_; }
  // Samples emitted per channel (strain, motor, imu, pose, truth; no loadcell).
  const ChannelCounts& emitted() const { return emitted_; }

 private:
  struct ScheduledStep {
    int64_t step = 0;
    int rotor = 0;  // 0-based
    double scale = 1.0;
  };

  void EmitStrain(SampleSink* sink);
  void EmitMotor(SampleSink* sink);
  void EmitImu(const MultiArmPlantState& derivative, SampleSink* sink);
  void EmitPose(SampleSink* sink);
  void EmitTruth(SampleSink* sink);
  // Steps between two samples of a sensor; 0: off.
  int64_t SensorEvery(const SensorRate& rate) const;

  VehicleDescription vehicle_;
  Scenario scenario_;
  int64_t step_us_;
  int64_t total_steps_;
  int64_t control_every_steps_;
  int64_t step_index_ = 0;

  MultiArmHover hover_;
  Trajectory trajectory_;
  MultiArmAutopilot autopilot_;
  ReferencePoint reference_;
  MultiArmRotorCommand command_;

  MultiArmPlantState state_;
  MultiArmPlantInput input_;
  std::array<double, kMaxArms> efficiency_{};  // s_i
  GaussianSource turbulence_noise_;
  std::vector<GaussMarkov> turbulence_;  // eta_i, one per rotor
  std::vector<ScheduledStep> thrust_steps_;
  size_t next_thrust_step_ = 0;
  std::vector<FaultEvent> fault_events_;

  int64_t strain_every_ = 0, motor_every_ = 0, imu_every_ = 0, pose_every_ = 0, truth_every_ = 0;
  GaussianSource strain_noise_, motor_noise_, imu_noise_, pose_noise_;
  int32_t strain_seq_ = 0, motor_seq_ = 0, imu_seq_ = 0, pose_seq_ = 0;
  ChannelCounts emitted_;
};

}  // namespace birotor
