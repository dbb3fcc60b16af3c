// The simulation engine: integrates the 12-state plant of model/plant.h
// with RK4 at a fixed step, drives it with the flight controller (or the bench
// profile), and emits noisy sensor samples, truth and configured faults at
// exact multiples of the step. Deterministic from the scenario seed.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "controller/seq_stream_lock.h"
#include "model/equilibrium.h"
#include "model/plant.h"
#include "samples/rotor_count.h"
#include "samples/sample_sink.h"
#include "simulator/bench_profile.h"
#include "simulator/esc_command_rule.h"
#include "simulator/fault_event.h"
#include "simulator/flight_controller.h"
#include "simulator/ground_phase.h"
#include "simulator/noise.h"
#include "simulator/scenario.h"
#include "simulator/strain_faults.h"
#include "simulator/trajectory.h"

namespace birotor {

// Samples emitted per channel (a strain sample lost in a gap is not counted).
struct ChannelCounts {
  int64_t strain = 0, motor = 0, imu = 0, pose = 0, loadcell = 0, truth = 0;
};

class Simulator {
 public:
  // The scenario must have been validated (LoadScenario does it), for the
  // birotor (arm_count 2: entries 0 and 1 of its per-arm lists are used).
  explicit Simulator(const Scenario& scenario);

  // Emits the samples due at the current time, then advances one step.
  // Returns false (and does nothing) once the scenario duration is reached.
  // Does not allocate except to record fault events.
  bool Step(SampleSink* sink);

  // Steps until done.
  void Run(SampleSink* sink);

  bool done() const { return step_index_ >= total_steps_; }
  double time_s() const { return static_cast<double>(step_index_) * scenario_.step_s; }
  // Simulated time of the current step plus the offset [us].
  int64_t utime() const { return utime_offset_us_ + step_index_ * step_us_; }
  int64_t total_steps() const { return total_steps_; }

  // Added to every utime (for --wall-clock); call before the first step.
  void set_utime_offset_us(int64_t offset_us) { utime_offset_us_ = offset_us; }

  // The simulator as the vehicle's ESCs: after the ground phase (if any) the
  // rotor commands come from OfferMotorCommand (an external controller,
  // MOTOR_COMMAND) instead of the built-in autopilot. The ESCs hold the last
  // good command (before the first one: the rotor speeds of the start
  // state); when none was accepted for command_timeout_s they command 0 (the
  // motors spool down with tau_m) and command_timed_out() says so until the
  // next one. Call before the first step.
  void UseExternalCommands(double command_timeout_s);
  // Emits the scenario's position reference (ReferenceAt) as a Setpoint
  // (SampleSink::OnSetpoint, channel SETPOINT) every 1 / rate_hz, stamped
  // with the time it is meant for: the trajectory as a planner would send
  // it to an external controller. Call before the first step.
  void EmitSetpoints(double rate_hz);
  // A command (seq, stamp utime [us], speeds [rad/s]) arrived at the current
  // step. The contract's rule for any motor interface: one commander at a
  // time (the first seq stream; another is counted and ignored until the
  // first has been silent for the command timeout), stamps checked against
  // the ESCs' clock (older than the timeout, not newer than the newest run,
  // or later than kEscFutureWindowS: refused), a speed that is not finite or
  // outside [0, omega_max] refused (the last good command is held, then the
  // timeout spools the motors down).
  EscVerdict OfferMotorCommand(int32_t seq, int64_t utime, const double (&omega_cmd_rad_s)[kBirotorRotors]);
  const EscCounters& esc_counters() const { return esc_ ? esc_->counters() : no_commands_; }
  bool external_commands() const { return external_commands_; }
  bool command_timed_out() const { return esc_ && esc_->timed_out(); }
  int64_t command_timeouts() const { return esc_ ? esc_->timeouts() : 0; }
  // The scenario's position reference at simulated time t_s (trajectory
  // time counts from the end of the ground phase).
  ReferencePoint ReferenceAt(double t_s) const { return trajectory_.At(t_s - scenario_.ground.FlightStartS()); }

  const Scenario& scenario() const { return scenario_; }
  const PlantState& state() const { return state_; }
  // mu_i = s_i (1 + eta_i) over the step about to be taken.
  const PlantInput& input() const { return input_; }
  // Hover equilibrium of the scenario's vehicle (the flight start state).
  const Equilibrium& hover_equilibrium() const { return equilibrium_; }
  const ReferencePoint& reference() const { return reference_; }
  const std::vector<FaultEvent>& fault_events() const { return fault_events_; }
  // Ground phase: true while the ground supports the body.
  bool on_ground() const { return ground_.on_ground(); }
  // Time of the first lift-off [us] (with the offset); -1 before it or
  // without a ground phase.
  int64_t liftoff_utime() const { return ground_.liftoff_utime(); }
  // Zero offset o_i(t) of gauge i at time t_s (gauge model, scenario.h) [rad].
  double GaugeOffsetRad(int gauge, double t_s) const;
  const ChannelCounts& emitted() const { return emitted_; }

 private:
  struct Decimation {
    bool enabled = false;
    int64_t every_steps = 1;
    bool Due(int64_t step) const { return enabled && step % every_steps == 0; }
  };
  struct ScheduledStep {
    int64_t step = 0;
    int rotor = 0;  // 0-based
    double scale = 1.0;
  };

  void EmitStrain(int64_t utime, SampleSink* sink);
  void EmitMotor(int64_t utime, SampleSink* sink);
  void EmitImu(int64_t utime, const PlantState& derivative, SampleSink* sink);
  void EmitPose(int64_t utime, SampleSink* sink);
  void EmitLoadCell(int64_t utime, SampleSink* sink);
  void EmitTruth(int64_t utime, SampleSink* sink);
  void EmitSetpoint(int64_t utime, double t_s, SampleSink* sink);
  double TrueForce(int rotor) const;
  PlantState Derivative(const PlantState& x) const;
  // Rotor speed commands of the ground phase and the landing, or the
  // controller's; t_s is the simulated time of the step.
  RotorCommand Command(double t_s);
  bool InWindow(const TimeWindow& window, int64_t t_us) const { return InTimeWindow(window, t_us, utime_offset_us_); }
  void RecordFault(FaultKind kind, int64_t utime, int32_t seq, int rotor, double value);

  Scenario scenario_;
  BirotorParams vehicle_;  // BirotorModelOf(scenario_.vehicle)
  bool clamped_body_;
  int64_t step_us_;
  int64_t total_steps_;
  int64_t step_index_ = 0;
  int64_t utime_offset_us_ = 0;

  Equilibrium equilibrium_;
  Trajectory trajectory_;
  FlightController controller_;
  BenchCommander bench_;
  ReferencePoint reference_;

  PlantState state_;
  PlantInput input_;
  RotorCommand command_;
  double efficiency_[kBirotorRotors] = {1.0, 1.0};  // s_i
  GaussMarkov turbulence_[kBirotorRotors];
  std::vector<ScheduledStep> thrust_steps_;
  size_t next_thrust_step_ = 0;

  GroundPhase ground_;                                   // scenario.ground
  double rotor_angle_rad_[kBirotorRotors] = {0.0, 0.0};  // theta_i for the harmonic pickup, in [0, 2 pi)

  Decimation setpoint_;
  Decimation control_, strain_, motor_, imu_, pose_, loadcell_, truth_;
  GaussianSource turbulence_noise_, strain_noise_, strain_jitter_noise_, motor_noise_, imu_noise_, pose_noise_,
      loadcell_noise_, fault_noise_;

  // External commands (UseExternalCommands).
  bool external_commands_ = false;
  static constexpr EscCounters no_commands_{};
  RotorCommand external_command_;  // the newest accepted (before any: the start state's speeds)
  std::unique_ptr<EscCommandRule> esc_;

  StrainFaultInjector<StrainSample> strain_faults_;

  int32_t setpoint_seq_ = 0;
  int32_t strain_seq_ = 0, motor_seq_ = 0, imu_seq_ = 0, pose_seq_ = 0, loadcell_seq_ = 0;
  ChannelCounts emitted_;
  std::vector<FaultEvent> fault_events_;
};

}  // namespace birotor
