#include "evaluation/multi_arm_closed_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "model/multi_arm_linearization.h"
#include "numerics/time_units.h"
#include "simulator/multi_arm_simulator.h"
#include "simulator/sample_clock.h"

namespace birotor {
namespace {

// Routes the simulator's samples: POSE and IMU to the controller, TRUTH_N
// into the run, all of them to the efficiency provider and the log.
class LoopSink : public SampleSink {
 public:
  LoopSink(MultiArmController* controller, const MultiArmSimulator* simulator, const MultiArmClosedLoopOptions& options,
           MultiArmClosedLoopRun* run)
      : controller_(controller), simulator_(simulator), options_(options), run_(run) {}

  void OnImu(const ImuSample& sample) override {
    controller_->OnImu(sample);
    Forward([&](SampleSink* sink) { sink->OnImu(sample); });
  }
  void OnPose(const PoseSample& sample) override {
    controller_->OnPose(sample);
    Forward([&](SampleSink* sink) { sink->OnPose(sample); });
  }
  void OnStrainN(const MultiArmStrainSample& sample) override {
    Forward([&](SampleSink* sink) { sink->OnStrainN(sample); });
  }
  void OnMotorN(const MultiArmMotorSample& sample) override {
    Forward([&](SampleSink* sink) { sink->OnMotorN(sample); });
  }
  void OnLoadCellN(const MultiArmLoadCellSample& sample) override {
    Forward([&](SampleSink* sink) { sink->OnLoadCellN(sample); });
  }
  void OnTruthN(const MultiArmTruthSample& sample) override {
    MultiArmTrackedSample tracked;
    tracked.utime = sample.utime;
    tracked.position_m = Eigen::Vector2d(sample.x_m, sample.z_m);
    tracked.phi_rad = sample.phi_rad;
    tracked.velocity_m_s = Eigen::Vector2d(sample.x_dot_m_s, sample.z_dot_m_s);
    tracked.reference_m = simulator_->ReferenceAt(simulator_->time_s()).position_m;
    run_->samples.push_back(tracked);
    Forward([&](SampleSink* sink) { sink->OnTruthN(sample); });
  }

 private:
  template <typename Call>
  void Forward(const Call& call) {
    if (options_.efficiency != nullptr) call(options_.efficiency);
    if (options_.log != nullptr) call(options_.log);
  }

  MultiArmController* controller_;
  const MultiArmSimulator* simulator_;
  const MultiArmClosedLoopOptions& options_;
  MultiArmClosedLoopRun* run_;
};

bool WithinBounds(const std::array<double, kMaxArms>& omega_rad_s, int arm_count, double omega_max_rad_s) {
  for (int i = 0; i < arm_count; ++i) {
    const double omega = omega_rad_s[static_cast<size_t>(i)];
    if (!std::isfinite(omega) || omega < 0.0 || omega > omega_max_rad_s) return false;
  }
  return true;
}

}  // namespace

void TrueEfficiencyProvider::OnTruthN(const MultiArmTruthSample& sample) {
  newest_.utime = sample.utime;
  newest_.n_rotors = sample.n_arms;
  newest_.valid = true;  // status 0: no deficit, mismatch nor converging (the truth)
  newest_.rotor_fault_bits = 0;
  for (int i = 0; i < sample.n_arms; ++i) {
    const size_t rotor = static_cast<size_t>(i);
    newest_.thrust_scale[rotor] = sample.thrust_scale[rotor];
    newest_.thrust_scale_std[rotor] = 0.0;
    newest_.force_n[rotor] = sample.force_n[rotor];  // exact: sigma 0
    newest_.force_std_n[rotor] = 0.0;
    if (sample.thrust_scale[rotor] < 1.0 - fault_margin_) newest_.rotor_fault_bits |= 1 << i;
  }
  fresh_ = true;
}

bool TrueEfficiencyProvider::Latest(int64_t /*now_us*/, RotorEfficiencyEstimate* estimate) {
  if (!fresh_) return false;
  *estimate = newest_;
  fresh_ = false;
  return true;
}

MultiArmFlightFigures FiguresOf(const MultiArmClosedLoopRun& run, double settling_band_m) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  MultiArmFlightFigures figures;
  const std::vector<MultiArmTrackedSample>& samples = run.samples;
  if (samples.empty()) return figures;
  double sum_squared_m2 = 0.0;
  size_t change = 0;  // first sample of the reference's last move; 0: none
  bool was_moving = false;
  double max_altitude_deviation_m = kNaN;
  for (size_t k = 0; k < samples.size(); ++k) {
    const MultiArmTrackedSample& s = samples[k];
    sum_squared_m2 += (s.position_m - s.reference_m).squaredNorm();
    figures.max_tilt_rad = std::max(figures.max_tilt_rad, std::abs(s.phi_rad));
    const bool moving = k > 0 && s.reference_m != samples[k - 1].reference_m;
    if (moving && !was_moving) change = k;  // the start of a move (a step: one sample)
    was_moving = moving;
    if (run.fault_utime >= 0 && s.utime >= run.fault_utime) {
      const double deviation_m = std::abs(s.position_m.y() - s.reference_m.y());
      max_altitude_deviation_m =
          std::isnan(max_altitude_deviation_m) ? deviation_m : std::max(max_altitude_deviation_m, deviation_m);
    }
  }
  figures.rms_position_error_m = std::sqrt(sum_squared_m2 / static_cast<double>(samples.size()));
  figures.max_altitude_deviation_m = max_altitude_deviation_m;
  figures.settling_s = kNaN;
  if (change == 0) {
    figures.overshoot_m = kNaN;
    return figures;
  }
  const Eigen::Vector2d start_m = samples[change - 1].reference_m;
  const Eigen::Vector2d final_m = samples.back().reference_m;
  const Eigen::Vector2d direction = (final_m - start_m).normalized();
  size_t last_outside = change;
  for (size_t k = change; k < samples.size(); ++k) {
    figures.overshoot_m = std::max(figures.overshoot_m, (samples[k].position_m - final_m).dot(direction));
    if ((samples[k].position_m - final_m).norm() > settling_band_m) last_outside = k;
  }
  if (last_outside + 1 < samples.size())
    figures.settling_s = ElapsedSeconds(samples[last_outside + 1].utime, samples[change].utime);
  return figures;
}

MultiArmClosedLoopRun RunMultiArmClosedLoop(const VehicleDescription& vehicle, const Scenario& scenario,
                                            const ControllerConfig& config, const MultiArmClosedLoopOptions& options) {
  if (scenario.mode != "flight" || scenario.ground.enabled) {
    throw std::invalid_argument("scenario '" + scenario.name +
                                "': the N-rotor lock-step loop flies mode flight without a ground phase");
  }
  MultiArmSimulator simulator(vehicle, scenario);
  simulator.UseExternalCommands();
  ControllerConfig lock_step_config = config;
  lock_step_config.mpc.deadline_clock = MpcDeadlineClock::kWork;
  MultiArmController controller(vehicle, lock_step_config, simulator.hover());
  MultiArmClosedLoopRun run;
  run.mode = controller.mode();
  run.arm_count = vehicle.arm_count;
  run.omega_max_rad_s = vehicle.omega_max_rad_s;
  const int64_t control_every_steps = StepsPerSample(controller.rate_hz(), scenario.step_s);
  const int64_t total_steps = std::llround(scenario.duration_s / scenario.step_s);
  run.samples.reserve(
      static_cast<size_t>(total_steps / StepsPerSample(scenario.sensors.truth.rate_hz, scenario.step_s) + 1));
  run.commands_rad_s.reserve(static_cast<size_t>(total_steps / control_every_steps + 1));
  if (controller.model_predictive()) run.mpc_solve_cpu_s.reserve(run.commands_rad_s.capacity());
  LoopSink sink(&controller, &simulator, options, &run);
  RotorEfficiencyEstimate estimate, newest;
  bool fresh = false;  // newest not yet handed to the controller
  for (int64_t k = 0; !simulator.done(); ++k) {
    if (k % control_every_steps == 0) {
      const int64_t now_us = simulator.utime();
      if (fresh) controller.OnEfficiency(newest);
      fresh = false;
      const MultiArmRotorCommand command = controller.Update(now_us, simulator.ReferenceAt(simulator.time_s()));
      simulator.OfferRotorCommands(command.omega_cmd_rad_s);
      run.commands_rad_s.push_back(command.omega_cmd_rad_s);
      if (run.descent_utime < 0 && controller.degradation().descending && !simulator.fault_events().empty())
        run.descent_utime = now_us;
      if (controller.model_predictive() && controller.mpc_solves() > static_cast<int64_t>(run.mpc_solve_cpu_s.size()))
        run.mpc_solve_cpu_s.push_back(controller.last_mpc_result().solve_cpu_s);
      if (!WithinBounds(command.omega_cmd_rad_s, vehicle.arm_count, vehicle.omega_max_rad_s))
        ++run.commands_out_of_bounds;
    }
    simulator.Step(&sink);
    // Every estimate as it arrives, as the N-rotor node takes FORCE_N: its
    // evidence noted (the floor's run counts estimates, not periods), the
    // newest flown in the next period.
    if (options.efficiency != nullptr && options.efficiency->Latest(simulator.utime(), &estimate)) {
      newest = controller.NoteReport(estimate, simulator.utime());
      fresh = true;
    }
  }
  run.saturated_periods = controller.saturated_periods();
  run.degradation = controller.degradation();
  run.mpc_solves = controller.mpc_solves();
  run.mpc_fallbacks = controller.mpc_fallbacks();
  for (const FaultEvent& event : simulator.fault_events()) {
    if (event.kind == FaultKind::kThrustStep) {
      run.fault_utime = event.utime;
      break;
    }
  }
  return run;
}

}  // namespace birotor
