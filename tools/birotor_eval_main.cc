// birotor-eval: force error against TRUTH for every method on every reference
// scenario (simulated in-process) or on one input log, as a Markdown table;
// optional PNG plots (thesis figures 5.1, 5.2). --control: the closed-loop
// control figures of both controller modes instead.
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "evaluation/closed_loop.h"
#include "evaluation/control_cases.h"
#include "evaluation/control_metrics.h"
#include "evaluation/descent_floor.h"
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
#include "tools/eval_mismatch_targets.h"
#include "tools/eval_multi_arm_accuracy.h"
#include "tools/eval_multi_arm_control.h"
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

// The scenarios of the estimator table by default: the reference flights,
// then (issue 27) vehicles that differ from the reference file the estimator keeps.
std::vector<std::string> DefaultScenarios() {
  std::vector<std::string> scenarios = {"hover",           "gentle",         "aggressive",   "thrust_loss",
                                        "density",         "sensor_faults",  "gauge_offset", "gauge_drift",
                                        "gauge_vibration", "gauge_airborne", "bench_gauge"};
  for (const char* name :
       {"mismatch_stiffness_plus20", "mismatch_stiffness_minus20", "mismatch_tip_mass_plus20",
        "mismatch_tip_mass_minus20", "mismatch_payload_plus15", "mismatch_payload_minus15", "mismatch_gauge_scale_0p7",
        "mismatch_gauge_scale_1p3", "mismatch_thrust_coeff_plus20", "mismatch_thrust_coeff_minus20",
        "mismatch_motor_lag_plus30", "mismatch_motor_lag_minus30", "mismatch_all"}) {
    scenarios.push_back(name);
  }
  return scenarios;
}

std::vector<std::string> ControlCaseNames() {
  std::vector<std::string> names;
  for (const ControlCase& c : ControlCases()) names.push_back(c.name);
  return names;
}

// birotor-eval's own command line (the defaults are the ones --help shows).
struct EvalCli {
  std::vector<std::string> scenarios = DefaultScenarios();
  std::vector<std::string> methods = EstimationMethodNames();
  std::string params_file = FindConfigFile("estimator.yaml");
  std::string scenario_dir;  // empty: each scenario is looked up as scenarios/<name>.yaml
  std::string log_path, markdown_out, plot_dir;
  std::vector<std::string> overrides;
  double duration_s = 0;
  EvalOptions eval_options;
  bool control = false;
  std::string controller_params = FindConfigFile("controller.yaml");
  std::vector<std::string> control_scenarios = ControlCaseNames();
  int seeds = 1;
  bool mpc = false;
  bool mismatch_targets = false;
  double min_usable_fraction = kDefaultMinUsableLogFraction;
  std::string vehicle_file;  // --vehicle: the N-arm EKF on this description
};

void AddEstimatorTableOptions(CLI::App& app, EvalCli* cli) {
  app.add_option("--scenarios", cli->scenarios,
                 "Scenario names: files <scenario-dir>/<name>.yaml, or without --scenario-dir the " +
                     ConfigSearchText("scenarios/<name>.yaml"))
      ->delimiter(',');
  app.add_option("--methods", cli->methods, "Methods (default: all)")
      ->delimiter(',')
      ->check(CLI::IsMember(EstimationMethodNames()));
  app.add_option("--params", cli->params_file,
                 "Estimator parameter file; default: the " + ConfigSearchText("estimator.yaml"));
  app.add_option("--scenario-dir", cli->scenario_dir, "Folder of the scenario files");
  app.add_option("--set", cli->overrides, "Simulator override section.key=value (repeatable), e.g. noise-free runs");
  app.add_option("--log", cli->log_path, "Evaluate one input log (with TRUTH) instead of simulating");
  app.add_option("--duration-s", cli->duration_s, "Simulate at most this long (0: whole scenario) [s]")
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--warmup-s", cli->eval_options.warmup_s, "Unscored start-up time [s]")->check(CLI::Range(0.0, 100.0));
  app.add_option("--markdown-out", cli->markdown_out, "Also write the table to this file");
  app.add_flag("--mismatch-targets", cli->mismatch_targets,
               "Issue 36's figures instead: every vehicle-mismatch case (docs/mismatch.md) and the matching "
               "hover, gentle, aggressive, thrust_loss on seeds 1..--seeds (default 5) with --params as given; "
               "VALID share, MAE and 2-sigma share of the VALID estimates, worst 2 s window, verdict per case");
  app.add_option("--plot-dir", cli->plot_dir, "Write <scenario>_<method>.png plots here");
  app.add_option("--vehicle", cli->vehicle_file,
                 "A vehicle description with N arms instead (e.g. config/vehicles/trirotor.yaml): the N-arm --methods "
                 "(docs/estimator.md, \"Methods for N arms\") on --scenarios: MAE and 2-sigma share per rotor, VALID "
                 "share, fault detection, false alarms; with --control the N-rotor controller lock-step (docs/"
                 "controller.md, \"Vehicles with N rotors\"; default cases lateral_step, aggressive, loss40_rotor1..3: "
                 "thrust_loss with that rotor at 60 % from 5 s), cascade and mode mpc, each on the nominal map and on "
                 "the estimated efficiencies (the loss cases also on the true ones, the bound): RMS error, max tilt, "
                 "settling within 2 cm, overshoot, altitude deviation after the loss, saturated periods, commands "
                 "outside [0, omega_max], MPC fallbacks / solves and solve CPU time p50 / p99 of the lock-step run");
}

void AddControlOptions(CLI::App& app, EvalCli* cli) {
  app.add_flag("--mpc", cli->mpc,
               "--control: also fly the model predictive controller without and with the estimated efficiencies "
               "(mode mpc, docs/mpc.md) and add its comparison with the force-feedback cascade; fails if any MPC "
               "command is outside [0, omega_max] or over the rate limit");
  app.add_flag("--control", cli->control,
               "Control figures instead: fly each case (--scenarios: a case name of docs/controller.md or a "
               "scenario name; default every case) closed loop (birotor-sim --controller) in both controller "
               "modes with the same gains on the same seeds; report RMS position error, and from the fault (or "
               "lift-off) over 3 s the peak tilt and altitude deviation, the time back within 5 cm and the "
               "touchdown speed (with the tilt, pitch rate and lower tip's speed at touchdown); then nominal vs "
               "force feedback per case (medians and worst seed)");
  app.add_option("--seeds", cli->seeds,
                 "--control: fly seeds 1..N of each case (1: the scenario's own seed); --mismatch-targets: seeds 1..N "
                 "(default 5)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--controller-params", cli->controller_params,
                 "Controller parameter file for --control; default: the " + ConfigSearchText("controller.yaml"));
}

void AddEvalOptions(CLI::App& app, CommonOptions* common, EvalCli* cli) {
  AddCommonOptions(app, common);
  app.remove_option(app.get_option("--lcm-url"));  // offline: reads files, never LCM (issue 24)
  AddEstimatorTableOptions(app, cli);
  AddControlOptions(app, cli);
  app.add_option("--min-usable-fraction", cli->min_usable_fraction,
                 "Refuse a --log whose readable events are less than this share of its bytes")
      ->check(CLI::Range(0.0, 1.0));
}

// A scenario by name: <scenario_dir>/<name>.yaml, or without a folder looked
// up in the config search path (a misspelt name lists them).
bool LoadNamedScenario(const std::string& name, const std::string& scenario_dir,
                       const std::vector<std::string>& overrides, Scenario* scenario, std::string* error) {
  try {
    std::string file = scenario_dir + "/" + name + ".yaml";
    if (scenario_dir.empty() && !FindScenario(name, &file, error)) return false;
    *scenario = LoadScenario(file, overrides);
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
  return true;
}

// The tables of --control, filled case by case.
struct ControlTables {
  std::string runs = ControlTableHeader();
  std::string comparison = ComparisonTableHeader();
  std::string mpc = MpcComparisonHeader();
  int64_t mpc_violations = 0;
  std::string lost;  // one "verdict: ..." line per lost flight (samples/flight_verdict.h)
};

// A lost flight's one line, for the end of the tables.
void NoteIfLost(const std::string& run, const char* mode, const ControlMetrics& metrics, ControlTables* tables) {
  if (metrics.verdict.lost) tables->lost += fmt::format("verdict: {} {}: {}\n", run, mode, metrics.verdict.Line());
}

// --mpc: the force-feedback cascade and the MPC without / with the efficiencies.
constexpr const char* kMpcModes[] = {"force_feedback", "mpc_nominal", "mpc"};
constexpr size_t kMpcModeCount = sizeof(kMpcModes) / sizeof(kMpcModes[0]);

// What the seeds of one case gave: the figures per mode and the first seed's traces.
struct CaseFigures {
  std::vector<ControlFigures> cascade[2];  // nominal, force_feedback
  std::vector<MpcRunFigures> mpc[kMpcModeCount];
  std::vector<int> seed_list;
  std::vector<ControlTrace> traces;
  double fault_time_s = -1;
};

// A flight that descended after its fault: where from, and its touchdown
// against the level descent's floor (evaluation/descent_floor.h).
void LogDescentFloor(const std::string& label, const ClosedLoopRun& run, const ControlMetrics& metrics,
                     const Scenario& scenario) {
  const DescentFloor floor = LevelDescentFloor(run, scenario);
  if (!floor.found) return;
  spdlog::info(
      "{}: descent from {:.3f} m at {:+.2f} m/s (t = {:.2f} s), level floor {:.2f} m/s (a = {:.3f} m/s^2); touchdown "
      "{:.2f} m/s = {:.2f} x floor, peak tilt from the fault {:.3f} rad; {} infeasible ({} from the sink, {} undone)",
      label, floor.height_m, floor.climb_m_s, floor.start_s, floor.touchdown_m_s, floor.sink_accel_m_s2,
      metrics.touchdown_speed_m_s, metrics.touchdown_speed_m_s / floor.touchdown_m_s, metrics.tilt_before_touchdown_rad,
      run.controller.infeasible, run.controller.infeasible_by_sink, run.controller.infeasible_undone);
}

// One seed of a case in both cascade modes: their rows, figures and (first
// seed) traces; with --mpc the force-feedback run is the MPC table's baseline.
void FlyCascadeModes(const ControlCase& c, const Scenario& scenario, bool first_seed, bool mpc,
                     const EstimatorConfig& estimator, const ControllerConfig& controller, CaseFigures* figures,
                     ControlTables* tables) {
  for (const bool force_feedback : {false, true}) {
    ControllerConfig config = controller;
    config.force_feedback = force_feedback;
    const ClosedLoopRun run = RunClosedLoop(scenario, estimator, config, ClosedLoopOptions());
    const ControlMetrics metrics = EvaluateControl(run);
    const char* mode = force_feedback ? "force_feedback" : "nominal";
    tables->runs += ControlTableRow(fmt::format("{} seed {}", c.name, scenario.seed), mode, metrics, run);
    NoteIfLost(fmt::format("{} seed {}", c.name, scenario.seed), mode, metrics, tables);
    figures->cascade[force_feedback ? 1 : 0].push_back(FiguresOf(metrics));
    spdlog::info(
        "{} seed {} {}: {:.1f} s flown in {:.2f} s; {} commands, {} descents, {} saturated; final "
        "efficiency {:.3f} {:.3f}; figures: {}",
        c.name, scenario.seed, mode, run.simulated_s, run.wall_s, run.controller.commands, run.controller.descents,
        run.controller.saturated, run.controller.efficiency[0], run.controller.efficiency[1],
        run.figures.Result().Line());
    LogDescentFloor(fmt::format("{} seed {} {}", c.name, scenario.seed, mode), run, metrics, scenario);
    if (first_seed) {
      figures->traces.push_back(TraceOf(run, mode));
      figures->fault_time_s = metrics.fault_time_s;
    }
    if (mpc && force_feedback) figures->mpc[0].push_back(MpcFiguresOf(run, metrics, config));
  }
}

// --mpc: one seed of a case with the MPC, without and with the efficiencies.
void FlyMpcModes(const ControlCase& c, const Scenario& scenario, const EstimatorConfig& estimator,
                 const ControllerConfig& controller, CaseFigures* figures, ControlTables* tables) {
  for (size_t m = 1; m < kMpcModeCount; ++m) {
    ControllerConfig config = controller;
    config.force_feedback = config.model_predictive = true;
    config.mpc.use_thrust_scale = std::strcmp(kMpcModes[m], "mpc") == 0;
    const ClosedLoopRun run = RunClosedLoop(scenario, estimator, config, ClosedLoopOptions());
    const ControlMetrics metrics = EvaluateControl(run);
    figures->mpc[m].push_back(MpcFiguresOf(run, metrics, config));
    tables->mpc_violations += figures->mpc[m].back().commands_out_of_bounds + figures->mpc[m].back().commands_over_rate;
    tables->runs += ControlTableRow(fmt::format("{} seed {}", c.name, scenario.seed), kMpcModes[m], metrics, run);
    NoteIfLost(fmt::format("{} seed {}", c.name, scenario.seed), kMpcModes[m], metrics, tables);
    spdlog::info("{} seed {} {}: {:.1f} s flown in {:.2f} s; {} solves, solve p99 {:.0f} us; figures: {}", c.name,
                 scenario.seed, kMpcModes[m], run.simulated_s, run.wall_s, run.mpc.solves, 1e6 * run.mpc.solve_p99_s,
                 run.figures.Result().Line());
    LogDescentFloor(fmt::format("{} seed {} {}", c.name, scenario.seed, kMpcModes[m]), run, metrics, scenario);
  }
}

// One case flown in both modes on each seed: the per-run rows, the
// comparison row and, with --plot-dir, the first seed's figure.
bool RunControlCase(const ControlCase& c, const EvalCli& cli, const EstimatorConfig& estimator,
                    const ControllerConfig& base_controller, ControlTables* tables) {
  const ControllerConfig controller = ControllerForCase(c, base_controller);
  CaseFigures figures;
  std::string error;
  for (int seed = 1; seed <= cli.seeds; ++seed) {
    std::vector<std::string> overrides = c.overrides;
    overrides.insert(overrides.end(), cli.overrides.begin(), cli.overrides.end());
    if (cli.seeds > 1) overrides.push_back("scenario.seed=" + std::to_string(seed));
    Scenario scenario;
    if (!LoadNamedScenario(c.scenario, cli.scenario_dir, overrides, &scenario, &error)) {
      ReportError(error);
      return false;
    }
    figures.seed_list.push_back(static_cast<int>(scenario.seed));
    FlyCascadeModes(c, scenario, seed == 1, cli.mpc, estimator, controller, &figures, tables);
    if (cli.mpc) FlyMpcModes(c, scenario, estimator, controller, &figures, tables);
  }
  for (size_t m = 0; cli.mpc && m < kMpcModeCount; ++m)
    tables->mpc += MpcComparisonRow(c.name, kMpcModes[m], figures.mpc[m]);
  tables->comparison +=
      ComparisonTableRow(c.name, CompareControl(figures.cascade[0], figures.cascade[1], figures.seed_list));
  const std::string png = cli.plot_dir + "/" + c.name + "_control.png";
  if (!cli.plot_dir.empty() &&
      !WriteControlPlot(figures.traces, c.name + ": nominal vs force_feedback", figures.fault_time_s, png, &error)) {
    ReportError("plot " + png + ": " + error);
    return false;
  }
  return true;
}

// --control: every case flown closed loop in both modes on each seed; the
// per-run table, then the comparison over seeds.
int RunControlTable(const std::vector<std::string>& names, const EvalCli& cli, const EstimatorConfig& estimator,
                    const ControllerConfig& controller) {
  ControlTables tables;
  for (const std::string& name : names) {
    // A case name, or a bare scenario flown as it is.
    const ControlCase* known = FindControlCase(name);
    const ControlCase c = known != nullptr ? *known : ControlCase{name, name, {}, name};
    if (!RunControlCase(c, cli, estimator, controller, &tables)) return kExitFailure;
  }
  const std::string table = tables.runs + "\n" + tables.comparison + (cli.mpc ? "\n" + tables.mpc : std::string());

  std::printf("%s", table.c_str());
  // Lost flights in one line each, after the tables (their figures unchanged).
  std::printf("%s", tables.lost.empty() ? "\nverdict: every flight kept its vehicle\n" : ("\n" + tables.lost).c_str());
  std::string error;
  if (!cli.markdown_out.empty() && !WriteFileAtomically(cli.markdown_out, table, &error)) return ReportError(error);
  // Issue 21: no MPC command outside [0, omega_max] or above the rate limit, ever.
  if (tables.mpc_violations > 0)
    return ReportError(fmt::format("{} MPC commands out of bounds or over the rate limit", tables.mpc_violations));
  return 0;
}

// --control: the controller file, the cases (the default list is the
// estimator's; the control table has its own), then the table.
int RunControlMode(const EvalCli& cli, bool scenarios_given, const EstimatorConfig& estimator) {
  if (!cli.log_path.empty()) return ReportError("--control flies scenarios; it does not take --log", kExitUsage);
  ControllerConfig controller;
  try {
    controller = LoadControllerConfig(cli.controller_params);
  } catch (const std::exception& error) {
    return ReportError(error.what());
  }
  return RunControlTable(scenarios_given ? cli.scenarios : cli.control_scenarios, cli, estimator, controller);
}

// The estimator table: the accuracy rows and the consistency rows (issue 27, docs/mismatch.md).
struct EstimatorTables {
  std::string accuracy = MarkdownTableHeader();
  std::string consistency = "\n" + MismatchTableHeader();
};

// One method on one scenario (or the log), scored.
struct MethodRun {
  std::string label;  // the scenario's name, or "log"
  EstimatorConfig config;
  EvalRun run;
  EvalResult result;
};

// Runs and scores one method; false with the error when nothing can be scored.
bool RunMethod(const EvalCli& cli, const std::string& name, const Scenario& scenario, const std::string& method,
               const EstimatorConfig& base_config, MethodRun* out, std::string* error) {
  out->config = base_config;
  out->config.method = method;
  // On a test stand the operator knows the body is held.
  if (scenario.mode == "bench") out->config.ekf.body_held = true;
  EvalRun& run = out->run;
  if (cli.log_path.empty()) {
    run = RunSimulatedScenario(scenario, out->config, cli.duration_s);
  } else if (!RunLog(cli.log_path, out->config, &run, error, cli.min_usable_fraction)) {
    return false;
  }
  if (!run.log_damage.empty() && method == cli.methods.front()) spdlog::warn("{}", run.log_damage);
  // A flight with a ground phase is scored from its lift-off.
  EvalOptions options = cli.eval_options;
  options.score_from_utime = run.liftoff_utime;
  out->result = Evaluate(run.forces, run.truth, run.stats.strain_fault_utimes, options);
  out->label = cli.log_path.empty() ? name : "log";
  // Nothing scored (no TRUTH, no FORCE, or all within the warm-up): a
  // table of NaN would look like a result.
  if (!cli.log_path.empty() && run.stats.input_packets == 0) {  // e.g. a birotor-replay output (issue 24)
    *error = fmt::format(
        "{}: no STRAIN, MOTOR, IMU or POSE input ({} events): --log re-runs the "
        "estimator on a recorded flight's inputs; a birotor-replay output has none "
        "(look at it with birotor-review or birotor-plot)",
        cli.log_path, run.stats.events);
    return false;
  }
  if (out->result.rotor[0].count == 0) {
    *error = fmt::format(
        "{} {}: no FORCE estimate paired with TRUTH after the {:.2f} s warm-up ({} FORCE, {} TRUTH): "
        "nothing to score",
        out->label, method, cli.eval_options.warmup_s, run.forces.size(), run.truth.size());
    return false;
  }
  return true;
}

// The method's rows of both tables and its log line.
void AddMethodRows(const MethodRun& r, const std::string& method, EstimatorTables* tables) {
  tables->accuracy += MarkdownTableRow(r.label, method, r.result);
  MismatchEvalOptions mismatch_options;
  mismatch_options.airborne_utime = r.run.liftoff_utime;
  tables->consistency +=
      MismatchTableRow(r.label, method, EvaluateMismatch(r.run.forces, r.run.truth, mismatch_options));
  const InputCounters& strain = r.run.health.inputs[static_cast<int>(InputChannel::kStrain)];
  spdlog::info(
      "{} {}: {:.1f} s simulated+estimated in {:.2f} s; strain received {} fused {} gated {} "
      "invalid {} out-of-order {} duplicates {} gaps {}; resets {}",
      r.label, method, r.run.simulated_s, r.run.wall_s, strain.received, strain.fused, strain.rejected_gate,
      strain.rejected_invalid, strain.out_of_order, strain.duplicates, strain.gaps, r.run.health.resets);
}

// <plot_dir>/<label>_<method>.png; a failure is reported, and the run goes on.
bool PlotMethod(const std::string& plot_dir, const MethodRun& r, const std::string& method) {
  const std::string png = plot_dir + "/" + r.label + "_" + method + ".png";
  ForcePlotOptions plot;
  plot.title = r.label + " - " + method;
  plot.scale_lines = ThrustScaleLines(r.config.ekf);
  if (r.result.step_rotor != 0) plot.markers.push_back(ThrustStepMarker(r.result.step_rotor, r.result.step_time_s));
  std::string error;
  if (!WriteForcePlot(r.run.forces, r.run.truth, plot, png, &error)) {
    ReportError("plot " + png + ": " + error);
    return false;
  }
  return true;
}

// Every method on every scenario (or on the log): the table on standard
// output and, through a temporary file renamed at the end, --markdown-out.
int RunEstimatorTable(const EvalCli& cli, const EstimatorConfig& base_config) {
  OutputFile markdown;
  std::string error;
  if (!CheckOutputs({cli.markdown_out}, {cli.log_path, cli.params_file}, &error) ||
      (!cli.markdown_out.empty() && !markdown.Open(cli.markdown_out, &error))) {
    return ReportError(error);
  }
  int exit_code = 0;
  EstimatorTables tables;
  for (const std::string& name : cli.scenarios) {
    Scenario scenario;
    if (cli.log_path.empty() && !LoadNamedScenario(name, cli.scenario_dir, cli.overrides, &scenario, &error)) {
      return ReportError(error);
    }
    for (const std::string& method : cli.methods) {
      MethodRun run;
      if (!RunMethod(cli, name, scenario, method, base_config, &run, &error)) return ReportError(error);
      AddMethodRows(run, method, &tables);
      if (!cli.plot_dir.empty() && !PlotMethod(cli.plot_dir, run, method)) exit_code = 1;
    }
  }
  const std::string table = tables.accuracy + tables.consistency;
  std::printf("%s", table.c_str());
  if (std::fflush(stdout) != 0) return ReportError("writing the table to standard output failed");
  if (markdown.is_open()) {
    markdown.Write(table);
    if (!markdown.Commit(&error)) return ReportError(error);
  }
  return exit_code;
}

}  // namespace
}  // namespace birotor

int main(int argc, char** argv) {
  using namespace birotor;
  CLI::App app{"birotor-eval: estimator accuracy against simulator truth"};
  CommonOptions common;
  EvalCli cli;
  AddEvalOptions(app, &common, &cli);
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-eval", common.log_level);

  EstimatorConfig base_config;
  try {
    base_config = LoadEstimatorConfig(cli.params_file);
  } catch (const std::exception& error) {
    return ReportError(error.what());
  }
  if (!cli.log_path.empty()) cli.scenarios = {cli.log_path};
  // Refuse unwritable outputs before minutes of simulation, not after.
  std::error_code fs_error;
  if (!cli.plot_dir.empty() && !std::filesystem::is_directory(cli.plot_dir) &&
      !std::filesystem::create_directories(cli.plot_dir, fs_error)) {
    return ReportError("cannot create --plot-dir " + cli.plot_dir);
  }
  if (!cli.vehicle_file.empty() && cli.control) {
    return RunMultiArmControl({cli.vehicle_file,
                               app.count("--scenarios") > 0 ? cli.scenarios : std::vector<std::string>{},
                               cli.controller_params, cli.scenario_dir, cli.overrides, cli.markdown_out, base_config});
  }
  if (cli.control) return RunControlMode(cli, app.count("--scenarios") > 0, base_config);
  if (!cli.vehicle_file.empty() && !cli.log_path.empty()) {
    return RunMultiArmLogAccuracy(cli.vehicle_file, cli.log_path, common.prefix, cli.eval_options);
  }
  if (!cli.vehicle_file.empty()) {
    if (app.count("--methods") == 0) cli.methods.clear();  // the file's estimator.method
    return RunMultiArmAccuracyMode(cli.vehicle_file, cli.scenarios, app.count("--scenarios") > 0, cli.methods,
                                   cli.overrides, base_config, cli.eval_options);
  }
  if (cli.mismatch_targets) {
    if (!cli.log_path.empty())
      return ReportError("--mismatch-targets flies its cases; it does not take --log", kExitUsage);
    const MismatchTargetsRunOptions options{app.count("--seeds") > 0 ? cli.seeds : 5, cli.overrides, cli.markdown_out};
    return RunMismatchTargets(
        options, base_config,
        [&cli](const std::string& name, const std::vector<std::string>& overrides, Scenario* scenario,
               std::string* error) { return LoadNamedScenario(name, cli.scenario_dir, overrides, scenario, error); });
  }
  return RunEstimatorTable(cli, base_config);
}
