// The lock-step closed loop for any VehicleDescription: MultiArmSimulator as
// the vehicle and its ESCs (UseExternalCommands), its POSE and IMU to the
// product's MultiArmController, at the controller's command rate (config/
// controller.yaml rate_hz, in mode mpc the mpc: section's) the controller's N
// rotor commands back, on one virtual clock. In mode mpc the solve deadline
// is a work budget (MpcDeadlineClock::kWork, as the birotor's lock-step
// loop), so the same seed flies the same on any machine. Optionally an efficiency provider (the N-arm estimator, fed
// every sample) whose every estimate the controller notes and whose newest
// it flies; without one the nominal map. The same scenario and seed give the same commands.
// birotor-eval --vehicle FILE --control uses it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "controller/controller_params.h"
#include "controller/multi_arm_controller.h"
#include "controller/wrench_allocation.h"
#include "model/vehicle_description.h"
#include "samples/sample_sink.h"
#include "simulator/scenario.h"

namespace birotor {

// The hook for an efficiency estimator: every simulator sample arrives
// through the SampleSink callbacks (STRAIN_N, MOTOR_N, IMU, POSE, TRUTH_N,
// in the order the simulator emits them); after every simulator step Latest
// is asked for the newest estimate at now_us (false: nothing new), which the
// controller notes (MultiArmController::NoteReport) and flies from the next
// control period on (the controller keeps the one it has until then).
class EfficiencyProvider : public SampleSink {
 public:
  virtual bool Latest(int64_t now_us, RotorEfficiencyEstimate* estimate) = 0;
};

// The bound a perfect estimator gives (a figure, not a product path): each
// rotor's true mu_i and thrust of TRUTH_N (turbulence included), sigma 0,
// VALID, flagged faulty below 1 - fault_margin.
class TrueEfficiencyProvider : public EfficiencyProvider {
 public:
  explicit TrueEfficiencyProvider(double fault_margin = 0.1) : fault_margin_(fault_margin) {}
  void OnTruthN(const MultiArmTruthSample& sample) override;
  bool Latest(int64_t now_us, RotorEfficiencyEstimate* estimate) override;

 private:
  double fault_margin_;
  RotorEfficiencyEstimate newest_;
  bool fresh_ = false;
};

struct MultiArmClosedLoopOptions {
  EfficiencyProvider* efficiency = nullptr;  // null: the nominal map
  SampleSink* log = nullptr;                 // also receives every simulator sample (may be null)
};

// One TRUTH_N sample with the reference flown then, world frame.
struct MultiArmTrackedSample {
  int64_t utime = 0;                                       // [us]
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();    // x, z [m]
  double phi_rad = 0.0;                                    // [rad]
  Eigen::Vector2d velocity_m_s = Eigen::Vector2d::Zero();  // x_dot, z_dot [m/s]
  Eigen::Vector2d reference_m = Eigen::Vector2d::Zero();   // x, z [m]
};

struct MultiArmClosedLoopRun {
  MultiArmControlMode mode = MultiArmControlMode::kTiltToMove;
  int arm_count = 0;
  double omega_max_rad_s = 0.0;                              // [rad/s]
  std::vector<MultiArmTrackedSample> samples;                // one per TRUTH_N sample
  std::vector<std::array<double, kMaxArms>> commands_rad_s;  // one per control period
  int64_t commands_out_of_bounds = 0;  // periods with a speed non-finite or outside [0, omega_max]
  int64_t saturated_periods = 0;       // periods whose allocation gave something up
  int64_t fault_utime = -1;            // first thrust step [us]; -1: none
  // The controller's controlled descent (MultiArmController::degradation()
  // at the end) and its first period at or after the fault [us]; -1: none.
  MultiArmDegradation degradation;
  int64_t descent_utime = -1;
  // Mode mpc: solves, fallbacks to the cascade (failed, late, non-finite or
  // infeasible) and each solve's CPU time of this thread [s] (a lock-step
  // figure: the virtual clock stands still during a solve).
  int64_t mpc_solves = 0;
  int64_t mpc_fallbacks = 0;
  std::vector<double> mpc_solve_cpu_s;
};

// The figures of one run (birotor-eval --vehicle FILE --control), from its TRUTH_N
// samples against the reference flown then.
struct MultiArmFlightFigures {
  double rms_position_error_m = 0.0;  // sqrt(mean |p - p_ref|^2) over every sample [m]
  double max_tilt_rad = 0.0;          // max |phi| over every sample [rad]
  // The reference's last change (a step or the end of a move): the time
  // from its start until |p - p_final| stays within settling_band_m; NaN
  // without a change or if it never settles [s].
  double settling_s = 0.0;
  // max of (p - p_final) . (p_final - p_start) / |p_final - p_start| after
  // the change; NaN without one [m].
  double overshoot_m = 0.0;
  // From the first thrust step on: max |z - z_ref| [m]; NaN without one.
  double max_altitude_deviation_m = 0.0;
};
MultiArmFlightFigures FiguresOf(const MultiArmClosedLoopRun& run, double settling_band_m);

// Flies the scenario (mode flight; its trajectory, faults, sensors and seed;
// its controller: section is not used, config's gains are) on vehicle with
// MultiArmController(vehicle, config). Throws std::invalid_argument as
// MultiArmSimulator does, and for a bench scenario or one with a ground
// phase (not flown by this loop yet).
MultiArmClosedLoopRun RunMultiArmClosedLoop(const VehicleDescription& vehicle, const Scenario& scenario,
                                            const ControllerConfig& config,
                                            const MultiArmClosedLoopOptions& options = {});

}  // namespace birotor
