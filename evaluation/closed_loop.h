// The lock-step closed loop: simulator (as the vehicle and its ESCs), the
// estimator pipeline (the daemon's code) and the flight controller in one
// process on one virtual clock. Every step the simulator's samples go to the
// estimator and the controller (and, encoded, to an optional log); the
// scenario's trajectory reaches the controller as SETPOINT messages (as
// birotor-sim --publish-setpoints sends them to birotor-controller); at the
// controller's rate its MOTOR_COMMAND goes to the simulator's ESCs. The same
// scenario and seed give the same bytes. birotor-sim --controller and
// birotor-eval --control use it.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

#include "controller/controller_params.h"
#include "controller/vehicle_controller.h"
#include "estimator/estimator_config.h"
#include "estimator/estimator_pipeline.h"
#include "samples/flight_figures.h"
#include "samples/motor_command.h"
#include "samples/samples.h"
#include "simulator/scenario.h"
#include "sinks/message_sink.h"

namespace birotor {

class Simulator;

struct ClosedLoopOptions {
  // The ESCs command 0 after this long without a MOTOR_COMMAND [s].
  double command_timeout_s = 0.1;
  // Channel prefix of the log.
  std::string prefix = "BIROTOR_";
  // The trajectory is sent as SETPOINT at this rate [Hz]; 0: not sent (a
  // test's before_step is then the only publisher).
  double setpoint_rate_hz = 100.0;
  // ESTIMATOR_STATUS and CONTROLLER_STATUS go into the log at this rate of
  // the vehicle clock, the daemons' default (EstimatorServiceOptions::
  // status_rate_hz, birotor-controller --status-rate-hz); 0: none [Hz].
  double status_rate_hz = 5.0;
  // Called before every simulator step (tests: an attacker's messages to
  // the controller or the ESCs at the simulator's current time).
  std::function<void(Simulator* simulator, VehicleController* controller)> before_step;
};

// One truth sample with the reference the controller was tracking then.
struct TrackedSample {
  TruthSample truth;
  Eigen::Vector2d reference_m = Eigen::Vector2d::Zero();  // world x, z [m]
};

struct ClosedLoopRun {
  std::vector<TrackedSample> samples;  // one per TRUTH sample
  std::vector<MotorCommand> commands;
  // The flight's figures (RMS, max tilt, fallbacks) by the one definition,
  // fed SETPOINT, TRUTH and MOTOR_COMMAND in the order the log gets them.
  FlightFigures figures;
  ControllerHealth controller;
  SetpointCounters setpoint;  // the controller's SETPOINT counters at the end
  MpcStats mpc;               // mode mpc: solves, fallbacks, solve times (zeros in other modes)
  PipelineHealth estimator;
  int64_t fault_utime = -1;      // first thrust step [us]; -1 if none
  int64_t liftoff_utime = -1;    // first lift-off of a ground start [us]; -1 if none
  bool has_ground = false;       // the scenario has a ground phase (a support at ground_z_m)
  double ground_z_m = 0;         // height of the support [m]
  double arm_length_m = 0;       // the flown vehicle's L (where its tips are) [m]
  int64_t command_timeouts = 0;  // ESC command timeouts
  // The ESCs' commander rule (EscCounters): second-commander commands,
  // the locked commander's refused in a conflict, entries into a conflict.
  int64_t esc_foreign = 0, esc_held = 0, esc_conflicts = 0;
  double simulated_s = 0;  // [s]
  double wall_s = 0;       // [s]
};

// Flies the scenario closed loop. log (may be null) receives every channel:
// the simulator's (SETPOINT, STRAIN, MOTOR, IMU, POSE, TRUTH, ...), FORCE,
// MOTOR_COMMAND, ESTIMATOR_STATUS and CONTROLLER_STATUS (the nodes' own
// encoders; the host-time figures, processing and solve times, left out). The scenario's own controller: section is not
// used (the gains are controller's).
ClosedLoopRun RunClosedLoop(const Scenario& scenario, const EstimatorConfig& estimator,
                            const ControllerConfig& controller, const ClosedLoopOptions& options,
                            MessageSink* log = nullptr);

}  // namespace birotor
