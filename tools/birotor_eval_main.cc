// birotor-eval: force error against TRUTH for every method on every reference
// scenario (simulated in-process) or on one input log, as a Markdown table;
// optional PNG plots (thesis figures 5.1, 5.2). --control: the closed-loop
// control figures of both controller modes instead.
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "evaluation/closed_loop.h"
#include "evaluation/control_cases.h"
#include "evaluation/control_metrics.h"
#include "evaluation/eval_metrics.h"
#include "evaluation/eval_runner.h"
#include "evaluation/mismatch_metrics.h"
#include "evaluation/mpc_comparison.h"
#include "params/controller_config_yaml.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "plot/control_plot.h"
#include "plot/force_plot.h"
#include "program/config_files.h"
#include "program/logging.h"
#include "program/program_options.h"
#include "transport/log_io.h"
#include "transport/output_file.h"

namespace birotor {
namespace {

// The flight as the control figure draws it: every 10th TRUTH sample (10 ms).
ControlTrace TraceOf(const ClosedLoopRun& run, const std::string& label) {
  ControlTrace trace;
  trace.label = label;
  if (run.samples.empty()) return trace;
  const int64_t start_utime = run.samples.front().truth.utime;
  for (size_t i = 0; i < run.samples.size(); i += 10) {
    const TrackedSample& s = run.samples[i];
    trace.t_s.push_back(1e-6 * static_cast<double>(s.truth.utime - start_utime));
    trace.x_error_m.push_back(s.truth.x_m - s.reference_m.x());
    trace.z_error_m.push_back(s.truth.z_m - s.reference_m.y());
    trace.tilt_rad.push_back(s.truth.phi_rad);
  }
  return trace;
}

// One case flown in both modes on each seed: the per-run rows, the
// comparison row and, with plot_dir, the first seed's figure.
bool RunControlCase(const ControlCase& c, int seeds, const std::string& scenario_dir,
                    const std::vector<std::string>& overrides, const EstimatorConfig& estimator,
                    const ControllerConfig& controller, const std::string& plot_dir, std::string* runs_table,
                    std::string* comparison_table, std::string* mpc_table, int64_t* mpc_violations) {
  std::vector<ControlFigures> figures[2];
  // --mpc: the force-feedback cascade and the MPC without / with the efficiencies.
  const std::vector<std::string> mpc_modes = {"force_feedback", "mpc_nominal", "mpc"};
  std::vector<MpcRunFigures> mpc_figures[3];
  std::vector<int> seed_list;
  std::vector<ControlTrace> traces;
  double fault_time_s = -1;
  for (int seed = 1; seed <= seeds; ++seed) {
    Scenario scenario;
    try {
      std::string file = scenario_dir + "/" + c.scenario + ".yaml", scenario_error;  // a misspelt name lists them
      if (scenario_dir.empty() && !FindScenario(c.scenario, &file, &scenario_error)) {
        ReportError(scenario_error);
        return false;
      }
      std::vector<std::string> all = c.overrides;
      all.insert(all.end(), overrides.begin(), overrides.end());
      if (seeds > 1) all.push_back("scenario.seed=" + std::to_string(seed));
      scenario = LoadScenario(file, all);
    } catch (const std::exception& e) {
      ReportError(e.what());
      return false;
    }
    seed_list.push_back(static_cast<int>(scenario.seed));
    for (const bool force_feedback : {false, true}) {
      ControllerConfig config = controller;
      config.force_feedback = force_feedback;
      const ClosedLoopRun run = RunClosedLoop(scenario, estimator, config, ClosedLoopOptions());
      const ControlMetrics metrics = EvaluateControl(run);
      const char* mode = force_feedback ? "force_feedback" : "nominal";
      *runs_table += ControlTableRow(fmt::format("{} seed {}", c.name, scenario.seed), mode, metrics, run);
      figures[force_feedback ? 1 : 0].push_back(FiguresOf(metrics));
      spdlog::info(
          "{} seed {} {}: {:.1f} s flown in {:.2f} s; {} commands, {} fallbacks, {} descents, {} saturated; final "
          "efficiency {:.3f} {:.3f}",
          c.name, scenario.seed, mode, run.simulated_s, run.wall_s, run.controller.commands, run.controller.fallbacks,
          run.controller.descents, run.controller.saturated, run.controller.efficiency[0],
          run.controller.efficiency[1]);
      if (seed == 1) {
        traces.push_back(TraceOf(run, mode));
        fault_time_s = metrics.fault_time_s;
      }
      if (mpc_table != nullptr && force_feedback) mpc_figures[0].push_back(MpcFiguresOf(run, metrics, config));
    }
    for (size_t m = 1; mpc_table != nullptr && m < mpc_modes.size(); ++m) {
      ControllerConfig config = controller;
      config.force_feedback = config.model_predictive = true;
      config.mpc.use_thrust_scale = mpc_modes[m] == "mpc";
      const ClosedLoopRun run = RunClosedLoop(scenario, estimator, config, ClosedLoopOptions());
      const ControlMetrics metrics = EvaluateControl(run);
      mpc_figures[m].push_back(MpcFiguresOf(run, metrics, config));
      *mpc_violations += mpc_figures[m].back().commands_out_of_bounds + mpc_figures[m].back().commands_over_rate;
      *runs_table += ControlTableRow(fmt::format("{} seed {}", c.name, scenario.seed), mpc_modes[m], metrics, run);
      spdlog::info("{} seed {} {}: {:.1f} s flown in {:.2f} s; {} solves, {} fallbacks, solve p99 {:.0f} us", c.name,
                   scenario.seed, mpc_modes[m], run.simulated_s, run.wall_s, run.mpc.solves, run.mpc.Fallbacks(),
                   1e6 * run.mpc.solve_p99_s);
    }
  }
  for (size_t m = 0; mpc_table != nullptr && m < mpc_modes.size(); ++m)
    *mpc_table += MpcComparisonRow(c.name, mpc_modes[m], mpc_figures[m]);
  *comparison_table += ComparisonTableRow(c.name, CompareControl(figures[0], figures[1], seed_list));
  std::string error;
  const std::string png = plot_dir + "/" + c.name + "_control.png";
  if (!plot_dir.empty() &&
      !WriteControlPlot(traces, c.name + ": nominal vs force_feedback", fault_time_s, png, &error)) {
    ReportError("plot " + png + ": " + error);
    return false;
  }
  return true;
}

// --control: every case flown closed loop in both modes on each seed; the
// per-run table, then the comparison over seeds.
int RunControlTable(const std::vector<std::string>& names, int seeds, const std::string& scenario_dir,
                    const std::vector<std::string>& overrides, const EstimatorConfig& estimator,
                    const ControllerConfig& controller, const std::string& markdown_out, const std::string& plot_dir,
                    bool mpc) {
  std::string runs = ControlTableHeader();
  std::string comparison = ComparisonTableHeader();
  std::string mpc_table = MpcComparisonHeader();
  int64_t mpc_violations = 0;
  for (const std::string& name : names) {
    // A case name, or a bare scenario flown as it is.
    const ControlCase* known = FindControlCase(name);
    const ControlCase c = known != nullptr ? *known : ControlCase{name, name, {}, name};
    if (!RunControlCase(c, seeds, scenario_dir, overrides, estimator, controller, plot_dir, &runs, &comparison,
                        mpc ? &mpc_table : nullptr, &mpc_violations)) {
      return kExitFailure;
    }
  }
  const std::string table = runs + "\n" + comparison + (mpc ? "\n" + mpc_table : std::string());

  std::printf("%s", table.c_str());
  std::string error;
  if (!markdown_out.empty() && !WriteFileAtomically(markdown_out, table, &error)) return ReportError(error);
  // Issue 21: no MPC command outside [0, omega_max] or above the rate limit, ever.
  if (mpc_violations > 0)
    return ReportError(fmt::format("{} MPC commands out of bounds or over the rate limit", mpc_violations));
  return 0;
}

}  // namespace
}  // namespace birotor

int main(int argc, char** argv) {
  using namespace birotor;
  CLI::App app{"birotor-eval: estimator accuracy against simulator truth"};
  CommonOptions common;
  AddCommonOptions(app, &common);
  app.remove_option(app.get_option("--lcm-url"));  // offline: reads files, never LCM (issue 24)
  std::vector<std::string> scenarios = {"hover",           "gentle",         "aggressive",   "thrust_loss",
                                        "density",         "sensor_faults",  "gauge_offset", "gauge_drift",
                                        "gauge_vibration", "gauge_airborne", "bench_gauge"};
  // Issue 27: vehicles that differ from the reference file the estimator keeps.
  for (const char* name :
       {"mismatch_stiffness_plus20", "mismatch_stiffness_minus20", "mismatch_tip_mass_plus20",
        "mismatch_tip_mass_minus20", "mismatch_payload_plus15", "mismatch_payload_minus15", "mismatch_gauge_scale_0p7",
        "mismatch_gauge_scale_1p3", "mismatch_thrust_coeff_plus20", "mismatch_thrust_coeff_minus20",
        "mismatch_motor_lag_plus30", "mismatch_motor_lag_minus30", "mismatch_all"}) {
    scenarios.push_back(name);
  }
  std::vector<std::string> methods = EstimationMethodNames();
  std::string params_file = FindConfigFile("estimator.yaml");
  std::string scenario_dir;  // empty: each scenario is looked up as scenarios/<name>.yaml
  std::string log_path, markdown_out, plot_dir;
  std::vector<std::string> overrides;
  std::vector<std::string> estimator_sets;
  double duration_s = 0;
  EvalOptions eval_options;
  app.add_option("--scenarios", scenarios,
                 "Scenario names: files <scenario-dir>/<name>.yaml, or without --scenario-dir the " +
                     ConfigSearchText("scenarios/<name>.yaml"))
      ->delimiter(',');
  app.add_option("--methods", methods, "Methods (default: all)")
      ->delimiter(',')
      ->check(CLI::IsMember(EstimationMethodNames()));
  app.add_option("--params", params_file,
                 "Estimator parameter file; default: the " + ConfigSearchText("estimator.yaml"));
  app.add_option("--scenario-dir", scenario_dir, "Folder of the scenario files");
  app.add_option("--set", overrides, "Simulator override section.key=value (repeatable), e.g. noise-free runs");
  app.add_option("--log", log_path, "Evaluate one input log (with TRUTH) instead of simulating");
  app.add_option("--duration-s", duration_s, "Simulate at most this long (0: whole scenario) [s]")
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--warmup-s", eval_options.warmup_s, "Unscored start-up time [s]")->check(CLI::Range(0.0, 100.0));
  app.add_option("--markdown-out", markdown_out, "Also write the table to this file");
  app.add_option("--plot-dir", plot_dir, "Write <scenario>_<method>.png plots here");
  bool control = false;
  std::string controller_params = FindConfigFile("controller.yaml");
  std::vector<std::string> control_scenarios;
  for (const ControlCase& c : ControlCases()) control_scenarios.push_back(c.name);
  int seeds = 1;
  bool mpc = false;
  app.add_flag("--mpc", mpc,
               "--control: also fly the model predictive controller without and with the estimated efficiencies "
               "(mode mpc, docs/mpc.md) and add its comparison with the force-feedback cascade; fails if any MPC "
               "command is outside [0, omega_max] or over the rate limit");
  app.add_flag("--control", control,
               "Control figures instead: fly each case (--scenarios: a case name of docs/controller.md or a "
               "scenario name; default every case) closed loop (birotor-sim --controller) in both controller "
               "modes with the same gains on the same seeds; report RMS position error, and from the fault (or "
               "lift-off) over 3 s the peak tilt and altitude deviation, the time back within 5 cm and the "
               "touchdown speed; then nominal vs force feedback per case (medians and worst seed)");
  app.add_option("--seeds", seeds, "--control: fly seeds 1..N of each case (1: the scenario's own seed)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--controller-params", controller_params,
                 "Controller parameter file for --control; default: the " + ConfigSearchText("controller.yaml"));
  double min_usable_fraction = kDefaultMinUsableLogFraction;
  app.add_option("--min-usable-fraction", min_usable_fraction,
                 "Refuse a --log whose readable events are less than this share of its bytes")
      ->check(CLI::Range(0.0, 1.0));
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-eval", common.log_level);

  EstimatorConfig base_config;
  try {
    base_config = LoadEstimatorConfig(params_file);
  } catch (const std::exception& error) {
    return ReportError(error.what());
  }
  if (!log_path.empty()) scenarios = {log_path};
  // Refuse unwritable outputs before minutes of simulation, not after.
  std::error_code fs_error;
  if (!plot_dir.empty() && !std::filesystem::is_directory(plot_dir) &&
      !std::filesystem::create_directories(plot_dir, fs_error)) {
    return ReportError("cannot create --plot-dir " + plot_dir);
  }
  if (control) {
    if (!log_path.empty()) return ReportError("--control flies scenarios; it does not take --log", kExitUsage);
    ControllerConfig controller;
    try {
      controller = LoadControllerConfig(controller_params);
    } catch (const std::exception& error) {
      return ReportError(error.what());
    }
    // The default list is the estimator's; the control table has its own.
    if (app.count("--scenarios") == 0) scenarios = control_scenarios;
    return RunControlTable(scenarios, seeds, scenario_dir, overrides, base_config, controller, markdown_out, plot_dir,
                           mpc);
  }
  // The Markdown goes to a temporary file next to it, renamed at the end.
  OutputFile markdown;
  std::string error;
  if (!CheckOutputs({markdown_out}, {log_path, params_file}, &error) ||
      (!markdown_out.empty() && !markdown.Open(markdown_out, &error))) {
    return ReportError(error);
  }
  int exit_code = 0;

  std::string table = MarkdownTableHeader();
  std::string consistency_table = "\n" + MismatchTableHeader();  // issue 27 (docs/mismatch.md)
  for (const std::string& name : scenarios) {
    Scenario scenario;
    if (log_path.empty()) {
      try {
        std::string file = scenario_dir + "/" + name + ".yaml", scenario_error;  // a misspelt name lists them
        if (scenario_dir.empty() && !FindScenario(name, &file, &scenario_error)) return ReportError(scenario_error);
        scenario = LoadScenario(file, overrides);
      } catch (const std::exception& e) {
        return ReportError(e.what());
      }
    }
    for (const std::string& method : methods) {
      EstimatorConfig config = base_config;
      config.method = method;
      // On a test stand the operator knows the body is held.
      if (scenario.mode == "bench") config.ekf.body_held = true;
      EvalRun run;
      if (log_path.empty()) {
        run = RunSimulatedScenario(scenario, config, duration_s);
      } else if (!RunLog(log_path, config, &run, &error, min_usable_fraction)) {
        return ReportError(error);
      }
      if (!run.log_damage.empty() && method == methods.front()) spdlog::warn("{}", run.log_damage);
      // A flight with a ground phase is scored from its lift-off.
      EvalOptions options = eval_options;
      options.score_from_utime = run.liftoff_utime;
      const EvalResult result = Evaluate(run.forces, run.truth, run.stats.strain_fault_utimes, options);
      const std::string label = log_path.empty() ? name : "log";
      // Nothing scored (no TRUTH, no FORCE, or all within the warm-up): a
      // table of NaN would look like a result.
      if (!log_path.empty() && run.stats.input_packets == 0) {  // e.g. a birotor-replay output (issue 24)
        return ReportError(
            fmt::format("{}: no STRAIN, MOTOR, IMU or POSE input ({} events): --log re-runs the "
                        "estimator on a recorded flight's inputs; a birotor-replay output has none "
                        "(look at it with birotor-review or birotor-plot)",
                        log_path, run.stats.events));
      }
      if (result.rotor[0].count == 0) {
        return ReportError(
            fmt::format("{} {}: no FORCE estimate paired with TRUTH after the {:.2f} s warm-up ({} FORCE, {} TRUTH): "
                        "nothing to score",
                        label, method, eval_options.warmup_s, run.forces.size(), run.truth.size()));
      }
      table += MarkdownTableRow(label, method, result);
      MismatchEvalOptions mismatch_options;
      mismatch_options.airborne_utime = run.liftoff_utime;
      consistency_table += MismatchTableRow(label, method, EvaluateMismatch(run.forces, run.truth, mismatch_options));
      const InputCounters& strain = run.health.inputs[static_cast<int>(InputChannel::kStrain)];
      spdlog::info(
          "{} {}: {:.1f} s simulated+estimated in {:.2f} s; strain received {} fused {} gated {} "
          "invalid {} out-of-order {} duplicates {} gaps {}; resets {}",
          label, method, run.simulated_s, run.wall_s, strain.received, strain.fused, strain.rejected_gate,
          strain.rejected_invalid, strain.out_of_order, strain.duplicates, strain.gaps, run.health.resets);
      if (!plot_dir.empty()) {
        const std::string png = plot_dir + "/" + label + "_" + method + ".png";
        ForcePlotOptions plot;
        plot.title = label + " - " + method;
        plot.scale_lines = ThrustScaleLines(config.ekf);
        if (result.step_rotor != 0) plot.markers.push_back(ThrustStepMarker(result.step_rotor, result.step_time_s));
        if (!WriteForcePlot(run.forces, run.truth, plot, png, &error)) {
          ReportError("plot " + png + ": " + error);
          exit_code = 1;
        }
      }
    }
  }
  table += consistency_table;
  std::printf("%s", table.c_str());
  if (std::fflush(stdout) != 0) return ReportError("writing the table to standard output failed");
  if (markdown.is_open()) {
    markdown.Write(table);
    if (!markdown.Commit(&error)) return ReportError(error);
  }
  return exit_code;
}
