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
#include "evaluation/control_metrics.h"
#include "evaluation/eval_metrics.h"
#include "evaluation/eval_runner.h"
#include "evaluation/mismatch_metrics.h"
#include "params/controller_config_yaml.h"
#include "params/estimator_config_yaml.h"
#include "plot/control_plot.h"
#include "plot/force_plot.h"
#include "simulator/scenario_yaml.h"
#include "transport/config_files.h"
#include "transport/log_io.h"
#include "transport/logging.h"
#include "transport/output_file.h"
#include "transport/program_options.h"

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

// --control: every scenario flown closed loop in both modes, one table, and
// with plot_dir one figure per scenario (<scenario>_control.png).
int RunControlTable(const std::vector<std::string>& scenarios, const std::string& scenario_dir,
                    const std::vector<std::string>& overrides, const EstimatorConfig& estimator,
                    const ControllerConfig& controller, const std::string& markdown_out, const std::string& plot_dir) {
  std::string table = ControlTableHeader();
  for (const std::string& name : scenarios) {
    Scenario scenario;
    try {
      std::string file = scenario_dir + "/" + name + ".yaml", scenario_error;  // a misspelt name lists them
      if (scenario_dir.empty() && !FindScenario(name, &file, &scenario_error)) return ReportError(scenario_error);
      scenario = LoadScenario(file, overrides);
    } catch (const std::exception& e) {
      return ReportError(e.what());
    }
    std::vector<ControlTrace> traces;
    double fault_time_s = -1;
    for (const bool force_feedback : {false, true}) {
      ControllerConfig config = controller;
      config.force_feedback = force_feedback;
      const ClosedLoopRun run = RunClosedLoop(scenario, estimator, config, ClosedLoopOptions());
      const ControlMetrics metrics = EvaluateControl(run);
      const char* mode = force_feedback ? "force_feedback" : "nominal";
      table += ControlTableRow(name, mode, metrics, run);
      spdlog::info("{} {}: {:.1f} s flown in {:.2f} s; {} commands, {} fallbacks, {} descents, {} saturated", name,
                   mode, run.simulated_s, run.wall_s, run.controller.commands, run.controller.fallbacks,
                   run.controller.descents, run.controller.saturated);
      traces.push_back(TraceOf(run, mode));
      if (run.fault_utime >= 0) fault_time_s = metrics.fault_time_s;
    }
    std::string error;
    const std::string png = plot_dir + "/" + name + "_control.png";
    if (!plot_dir.empty() &&
        !WriteControlPlot(traces, name + ": nominal vs force_feedback", fault_time_s, png, &error)) {
      return ReportError("plot " + png + ": " + error);
    }
  }
  std::printf("%s", table.c_str());
  std::string error;
  if (!markdown_out.empty() && !WriteFileAtomically(markdown_out, table, &error)) return ReportError(error);
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
  std::vector<std::string> control_scenarios = {"hover",       "gentle",  "aggressive",
                                                "thrust_loss", "density", "thrust_loss_severe"};
  app.add_flag("--control", control,
               "Control figures instead: fly each scenario closed loop (birotor-sim --controller) in both "
               "controller modes with the same gains and report RMS position error, peak tilt, altitude loss "
               "after the fault and the time back within 5 cm");
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
    return RunControlTable(scenarios, scenario_dir, overrides, base_config, controller, markdown_out, plot_dir);
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
