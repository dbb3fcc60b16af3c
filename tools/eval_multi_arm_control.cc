#include "tools/eval_multi_arm_control.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <exception>

#include "controller/controller_params.h"
#include "evaluation/estimated_efficiency_provider.h"
#include "evaluation/multi_arm_closed_loop.h"
#include "evaluation/multi_arm_descent_floor.h"
#include "numerics/percentile.h"
#include "params/controller_config_yaml.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "program/config_files.h"
#include "program/program_options.h"
#include "transport/output_file.h"

namespace birotor {
namespace {

// Settling band of the lateral step: 2 % of its 1 m [m].
constexpr double kSettlingBandM = 0.02;
// The loss cases: rotor k at 60 % of its thrust from 5 s of thrust_loss.
constexpr double kLossScale = 0.6;
constexpr char kLossPrefix[] = "loss40_rotor";
// The descent cases descentPP_rotorK: thrust_loss climbing to 1 m in 2 s,
// rotor K at (100 - PP) % from 5 s, 8 s long (the N-rotor loop has no
// ground: the touchdown is the crossing of the take-off level, z = 0).
constexpr char kDescentPrefix[] = "descent";
constexpr char kDescentClimb[] = "trajectory.waypoints=[{start_s: 0.0, duration_s: 2.0, x_m: 0.0, z_m: 1.0}]";
// The changed-vehicle case (the birotor's density_0.85, ct_-15): every rotor
// at 0.85 of its map from the start of a 10 s hover (air 15 % thinner, or
// c_T -15 %), a thrust step at 0 s so that the altitude deviation counts
// from the start.
constexpr char kDensityCase[] = "density85";
constexpr double kDensityScale = 0.85;

std::vector<std::string> DefaultCases() {
  return {"lateral_step", "aggressive", "loss40_rotor1", "loss40_rotor2", "loss40_rotor3", kDensityCase};
}

// The density85 case's scenario and overrides for arm_count rotors.
void DensityCase(int arm_count, std::string* scenario, std::vector<std::string>* overrides) {
  *scenario = "hover";
  overrides->push_back("scenario.duration_s=10.0");
  std::string steps;
  for (int k = 1; k <= arm_count; ++k)
    steps += fmt::format("{}{{time_s: 0.0, rotor: {}, scale: {}}}", k > 1 ? ", " : "", k, kDensityScale);
  overrides->push_back("faults.thrust_steps=[" + steps + "]");
}

// A case: a scenario name, loss40_rotorK (thrust_loss with rotor K at 60 %
// from 5 s), descentPP_rotorK or density85. *rotor: K, or 0 otherwise.
bool CaseScenario(const std::string& name, int arm_count, std::string* scenario, std::vector<std::string>* overrides,
                  int* rotor) {
  *rotor = 0;
  *scenario = name;
  if (name == kDensityCase) {
    DensityCase(arm_count, scenario, overrides);
    return true;
  }
  if (name.rfind(kDescentPrefix, 0) == 0) {
    int loss_percent = 0;
    if (std::sscanf(name.c_str(), "descent%d_rotor%d", &loss_percent, rotor) != 2 || loss_percent < 0 ||
        loss_percent > 100)
      return false;
    *scenario = "thrust_loss";
    overrides->push_back("trajectory.kind=waypoints");
    overrides->push_back(kDescentClimb);
    overrides->push_back("scenario.duration_s=8.0");
    overrides->push_back(
        fmt::format("faults.thrust_steps=[{{time_s: 5.0, rotor: {}, scale: {}}}]", *rotor, 1.0 - 0.01 * loss_percent));
    return true;
  }
  if (name.rfind(kLossPrefix, 0) != 0) return true;
  try {
    *rotor = std::stoi(name.substr(sizeof(kLossPrefix) - 1));
  } catch (const std::exception&) {
    return false;
  }
  *scenario = "thrust_loss";
  overrides->push_back(fmt::format("faults.thrust_steps=[{{time_s: 5.0, rotor: {}, scale: {}}}]", *rotor, kLossScale));
  return true;
}

std::string Figure(double value, const char* format) {
  return std::isnan(value) ? std::string("-") : fmt::format(fmt::runtime(format), value);
}

// Mode mpc: fallbacks / solves and the solve CPU time p50 / p99 [us] of the
// lock-step run; "-" for the cascade.
std::string MpcColumns(const MultiArmClosedLoopRun& run) {
  if (run.mpc_solves == 0) return "- | -";
  return fmt::format("{} / {} | {:.0f} / {:.0f}", run.mpc_fallbacks, run.mpc_solves,
                     1e6 * Percentile(run.mpc_solve_cpu_s, 0.5), 1e6 * Percentile(run.mpc_solve_cpu_s, 0.99));
}

std::string Row(const std::string& name, const std::string& map, const MultiArmClosedLoopRun& run) {
  const MultiArmFlightFigures f = FiguresOf(run, kSettlingBandM);
  const char* mode = run.mode == MultiArmControlMode::kFullyActuated ? "fully actuated" : "tilt to move";
  return fmt::format("| {} | {}{} | {} | {:.4f} | {:.4f} | {} | {} | {} | {} | {} | {} |\n", name, mode,
                     run.mpc_solves > 0 ? ", mpc" : "", map, f.rms_position_error_m, f.max_tilt_rad,
                     Figure(f.settling_s, "{:.2f}"), Figure(f.overshoot_m, "{:.3f}"),
                     Figure(f.max_altitude_deviation_m, "{:.4f}"), run.saturated_periods, run.commands_out_of_bounds,
                     MpcColumns(run));
}

// A descent case's row: the descent's start, the level floor, the
// touchdown and the peak tilt from the fault (evaluation/multi_arm_descent_floor.h).
std::string DescentRow(const std::string& name, const std::string& map, const MultiArmClosedLoopRun& run,
                       const VehicleDescription& vehicle, const Scenario& scenario) {
  const MultiArmDescent d = MultiArmDescentOf(run, vehicle, scenario);
  const MultiArmDegradation& g = run.degradation;
  const std::string start =
      fmt::format("{}{:.2f} s: {:.2f} m, {:+.2f} m/s", d.found ? "" : "fault ", d.start_s, d.height_m, d.climb_m_s);
  return fmt::format("| {} | {}{} | {} | {} / {} / {} | {} | {:.2f} | {} | {} | {:.3f} |\n", name,
                     run.mode == MultiArmControlMode::kFullyActuated ? "fully actuated" : "tilt to move",
                     run.mpc_solves > 0 ? ", mpc" : "", map, g.descents, g.infeasible, g.infeasible_by_sink, start,
                     d.floor_m_s, Figure(d.touchdown_m_s, "{:.2f}"), Figure(d.touchdown_m_s / d.floor_m_s, "{:.2f}"),
                     d.peak_tilt_rad);
}

// One case, nominal and on the estimated efficiencies (for a loss also on
// the true ones): its rows, or false with *error.
bool FlyCase(const std::string& name, const VehicleDescription& vehicle, const ControllerConfig& controller,
             const MultiArmControlInputs& inputs, std::string* rows, std::string* descent_rows, int64_t* out_of_bounds,
             std::string* error) {
  std::string scenario_name;
  std::vector<std::string> overrides;
  int rotor = 0;
  if (!CaseScenario(name, vehicle.arm_count, &scenario_name, &overrides, &rotor)) {
    *error = "case '" + name + "': not a scenario name, loss40_rotorK, descentPP_rotorK nor density85";
    return false;
  }
  if (rotor > vehicle.arm_count) {
    *rows += fmt::format("| {} | - | - | the vehicle has {} rotors | | | | | | | | |\n", name, vehicle.arm_count);
    return true;
  }
  overrides.insert(overrides.end(), inputs.overrides.begin(), inputs.overrides.end());
  std::string file = inputs.scenario_dir + "/" + scenario_name + ".yaml";
  if (inputs.scenario_dir.empty() && !FindScenario(scenario_name, &file, error)) return false;
  const Scenario scenario = LoadScenario(file, overrides, vehicle.arm_count);
  const bool descent_case = name.rfind(kDescentPrefix, 0) == 0;
  // The cascade, then mode mpc (the mpc: section; the cascade its fallback).
  for (const bool model_predictive : {false, true}) {
    ControllerConfig nominal = controller;
    nominal.force_feedback = false;
    nominal.model_predictive = model_predictive;
    const MultiArmClosedLoopRun run = RunMultiArmClosedLoop(vehicle, scenario, nominal);
    *rows += Row(name, "nominal", run);
    if (descent_case) *descent_rows += DescentRow(name, "nominal", run, vehicle, scenario);
    *out_of_bounds += run.commands_out_of_bounds;
    ControllerConfig with_efficiency = nominal;
    with_efficiency.force_feedback = true;
    EstimatedEfficiencyProvider estimate(vehicle, inputs.estimator);
    MultiArmClosedLoopOptions estimated;
    estimated.efficiency = &estimate;
    const MultiArmClosedLoopRun flown = RunMultiArmClosedLoop(vehicle, scenario, with_efficiency, estimated);
    *rows += Row(name, "estimated (N-arm EKF)", flown);
    if (descent_case) *descent_rows += DescentRow(name, "estimated (N-arm EKF)", flown, vehicle, scenario);
    *out_of_bounds += flown.commands_out_of_bounds;
    if (rotor == 0) continue;
    TrueEfficiencyProvider truth;
    MultiArmClosedLoopOptions options;
    options.efficiency = &truth;
    const MultiArmClosedLoopRun bound = RunMultiArmClosedLoop(vehicle, scenario, with_efficiency, options);
    *rows += Row(name, "true efficiency (bound)", bound);
    if (descent_case) *descent_rows += DescentRow(name, "true efficiency (bound)", bound, vehicle, scenario);
    *out_of_bounds += bound.commands_out_of_bounds;
  }
  return true;
}

}  // namespace

int RunMultiArmControl(const MultiArmControlInputs& inputs) {
  std::string rows, descent_rows, error;
  int64_t out_of_bounds = 0;
  try {
    const VehicleDescription vehicle = LoadVehicleDescription(inputs.vehicle_file);
    const ControllerConfig controller = LoadControllerConfig(inputs.controller_params);
    rows = fmt::format("N-rotor controller on '{}' ({} rotors), gains of {}\n\n", vehicle.name, vehicle.arm_count,
                       inputs.controller_params);
    rows +=
        "| case | mode | map | RMS error [m] | max tilt [rad] | settling [s] | overshoot [m] | altitude dev. after "
        "loss [m] | saturated periods | commands out of bounds | MPC fallbacks / solves | MPC solve CPU p50 / p99 "
        "[us], lock-step |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const std::string& name : inputs.cases.empty() ? DefaultCases() : inputs.cases) {
      if (!FlyCase(name, vehicle, controller, inputs, &rows, &descent_rows, &out_of_bounds, &error))
        return ReportError(error);
    }
    if (!descent_rows.empty()) {
      rows +=
          "\nDescents (from the fault; touchdown: the truth crossing z = 0, the take-off level)\n\n| case | mode | map "
          "| descents / infeasible / by sink | descent start: h, v | level floor [m/s] | touchdown [m/s] | touchdown "
          "/ floor | peak tilt [rad] |\n|---|---|---|---|---|---|---|---|---|\n" +
          descent_rows;
    }
  } catch (const std::exception& e) {
    return ReportError(e.what());
  }
  std::printf("%s", rows.c_str());
  if (!inputs.markdown_out.empty() && !WriteFileAtomically(inputs.markdown_out, rows, &error))
    return ReportError(error);
  if (out_of_bounds > 0) return ReportError(fmt::format("{} commands outside [0, omega_max]", out_of_bounds));
  return 0;
}

}  // namespace birotor
