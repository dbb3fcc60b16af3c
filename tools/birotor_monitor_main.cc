// birotor-monitor: a compact live view of a running estimator (FORCE,
// ESTIMATOR_STATUS) and, with a simulator, of its TRUTH; at the end the error
// figures of birotor-eval over every FORCE/TRUTH pair it received, or without
// TRUTH (a real vehicle, --no-truth or none within --truth-wait-s) a summary of
// the FORCE stream and the estimator's health; plus an optional PNG.
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "evaluation/eval_metrics.h"
#include "monitor/monitor_collector.h"
#include "monitor/monitor_view.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "plot/force_plot.h"
#include "program/logging.h"
#include "program/program_options.h"
#include "program/shutdown.h"
#include "sources/dropped_datagram_log.h"
#include "sources/message_source.h"
#include "sources/receive_loop.h"
#include "transport/host_clock.h"
#include "transport/lcm_session.h"

namespace birotor {
namespace {

struct MonitorOptions {
  CommonOptions common;
  std::string scenario_file;      // for the progress target and the table label; optional
  std::string label;              // scenario column of the table; default: scenario name or "live"
  double duration_s = 0;          // stop after this much vehicle time [s]; 0: no limit
  bool until_sim_ends = false;    // stop when TRUTH (FORCE without truth) has been silent for idle_s
  double idle_s = 1.0;            // [s]
  double startup_timeout_s = 30;  // give up if neither TRUTH nor FORCE arrives within this [s]
  bool no_truth = false;          // vehicle view from FORCE and ESTIMATOR_STATUS only
  double truth_wait_s = 3.0;      // FORCE but no TRUTH for this long: vehicle view [s]
  double stale_age_s = 0.1;       // an input older than this shows as stale [s]
  std::string params_file;        // the estimator's parameter file, for its thresholds; empty: defaults
  double interval_s = 0;          // view refresh [s]; 0: 0.2 on a terminal, 1.0 otherwise
  bool plain = false;             // one plain line per refresh even on a terminal
  bool quiet = false;             // no live view, final figures only
  std::string png;                // plot file; empty: none
  bool markdown = false;          // print birotor-eval's Markdown table too
  EvalOptions eval;
};

// True if path can be written (creating it if needed); a file created by the
// check is removed again, so a failed run leaves nothing behind.
bool CheckWritable(const std::string& path, std::string* error) {
  const bool existed = access(path.c_str(), F_OK) == 0;
  std::FILE* file = std::fopen(path.c_str(), "a");
  if (file == nullptr) {
    *error = "cannot write " + path + ": " + std::strerror(errno);
    return false;
  }
  std::fclose(file);
  if (!existed) std::remove(path.c_str());
  return true;
}

int Main(int argc, char** argv) {
  MonitorOptions options;
  CLI::App app{
      "birotor-monitor: live view of FORCE and ESTIMATOR_STATUS (and TRUTH from a simulator), then the error "
      "figures of birotor-eval over what was received, or without TRUTH a summary of the estimates and health"};
  AddCommonOptions(app, &options.common);
  app.add_option("--scenario", options.scenario_file,
                 "Scenario file the simulator runs (progress target and table label)");
  app.add_option("--label", options.label, "Scenario column of the table (default: scenario name or 'live')");
  app.add_option("--duration-s", options.duration_s, "Stop after this much vehicle time (0: no limit) [s]")
      ->check(CLI::Range(0.0, 1e6));
  app.add_flag("--until-sim-ends", options.until_sim_ends,
               "Stop when TRUTH (FORCE without truth) has been silent for --idle-s after the first one");
  app.add_option("--idle-s", options.idle_s, "Silence that means the simulator (or vehicle) stopped [s]")
      ->check(CLI::Range(0.05, 60.0));
  app.add_option("--startup-timeout-s", options.startup_timeout_s,
                 "Fail if neither TRUTH nor FORCE arrives within this [s]")
      ->check(CLI::Range(0.1, 3600.0));
  app.add_flag("--no-truth", options.no_truth,
               "Vehicle view: FORCE and ESTIMATOR_STATUS only, never wait for TRUTH (a real vehicle)");
  app.add_option("--truth-wait-s", options.truth_wait_s,
                 "FORCE arrives but no TRUTH within this: switch to the vehicle view, said on screen [s]")
      ->check(CLI::Range(0.1, 3600.0));
  app.add_option("--stale-age-s", options.stale_age_s,
                 "Show an input as STALE when its newest sample is older than this (vehicle clock) [s]")
      ->check(CLI::Range(1e-3, 3600.0));
  app.add_option("--params", options.params_file,
                 "Estimator parameter file the daemon runs, for its fault thresholds in the view and plot "
                 "(default: the built-in estimator defaults)");
  app.add_option("--interval-s", options.interval_s, "View refresh period (0: 0.2 on a terminal, 1 otherwise) [s]")
      ->check(CLI::Range(0.0, 60.0));
  app.add_flag("--plain", options.plain, "One plain line per refresh, even on a terminal");
  app.add_flag("--quiet", options.quiet, "No live view; final figures only");
  app.add_option("--png", options.png,
                 "Write the force plot (estimates with 1 sigma, truth, errors, thrust efficiency, flags) to this PNG");
  app.add_flag("--markdown", options.markdown, "Also print the figures as birotor-eval's Markdown table");
  app.add_option("--warmup-s", options.eval.warmup_s, "Unscored start-up time, as birotor-eval [s]")
      ->check(CLI::Range(0.0, 100.0));
  if (const std::optional<int> exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-monitor", options.common.log_level);

  double scenario_duration_s = options.duration_s;
  std::string label = options.label;
  if (!options.scenario_file.empty()) {
    try {
      const Scenario scenario = LoadScenario(options.scenario_file);
      if (scenario_duration_s <= 0) scenario_duration_s = scenario.duration_s;
      if (label.empty()) label = scenario.name;
    } catch (const std::exception& e) {
      return ReportError(e.what());
    }
  }
  if (label.empty()) label = "live";
  EkfOptions ekf;
  if (!options.params_file.empty()) {
    try {
      ekf = LoadEstimatorConfig(options.params_file).ekf;
    } catch (const std::exception& e) {
      return ReportError(e.what());
    }
  }
  std::string error;
  if (!options.png.empty() && !CheckWritable(options.png, &error)) {
    return ReportError(error);
  }

  std::unique_ptr<lcm::LCM> lcm = OpenLcm(options.common.lcm_url, &error);
  if (!lcm) {
    return ReportError(error);
  }
  InstallShutdownHandlers();
  const ChannelNames channels = MakeChannelNames(options.common.prefix);
  MonitorCollector collector(channels, scenario_duration_s > 0 ? scenario_duration_s + 5.0 : 60.0);
  // Inputs through the shared message source: on udpm our own LC02 reader,
  // which drops and counts fragments instead of reassembling them.
  std::unique_ptr<MessageSource> source = OpenLiveSource(options.common.lcm_url, lcm.get(), &error);
  if (!source || !source->Subscribe(collector.InputChannels(), &collector, &error)) return ReportError(error);
  DroppedDatagramLog dropped;
  spdlog::info("birotor-monitor {} listening on {} ({}): {} {} {}", BIROTOR_VERSION, options.common.lcm_url,
               source->Describe(), channels.truth, channels.force, channels.estimator_status);
  if (options.duration_s <= 0 && !options.until_sim_ends) {
    spdlog::info("neither --duration-s nor --until-sim-ends: runs until SIGINT/SIGTERM");
  }

  const bool terminal = isatty(STDOUT_FILENO) && !options.plain && !options.quiet;
  const double interval_s = options.interval_s > 0 ? options.interval_s : (terminal ? 0.2 : 1.0);
  const double start_s = SteadyClockS();
  double last_arrival_s = start_s;  // of the clock stream: TRUTH, or FORCE without truth
  size_t last_clock_count = 0;
  double first_force_s = -1;
  double last_view_s = start_s;
  size_t last_view_forces = 0;
  int64_t last_view_status = 0;
  bool view_drawn = false;
  bool timed_out = false;
  ViewContext context;
  context.scenario_duration_s = scenario_duration_s;
  context.truth_expected = !options.no_truth;
  context.stale_age_s = options.stale_age_s;
  context.thresholds = ThresholdWords(ThrustScaleLines(ekf));
  // A notice printed once above the live view (it scrolls with plain lines).
  const auto notice = [&](const std::string& text) {
    if (options.quiet) return;
    if (terminal && view_drawn) std::printf("\x1b[%dA", kTerminalViewLines);
    std::printf("%s%s\n", terminal ? "\x1b[K" : "", text.c_str());
    view_drawn = false;  // the view is drawn again below the notice
    std::fflush(stdout);
  };
  if (options.no_truth) notice("birotor-monitor: vehicle view (--no-truth): FORCE and ESTIMATOR_STATUS only");

  while (!ShutdownRequested()) {
    ReceiveUntil(source.get(), 0.05, SteadyClockUs() + 50000);
    if (source->finished()) {
      spdlog::error("{}; stopping", source->error());
      break;
    }
    dropped.Check(source->udp_counters());
    const double now_s = SteadyClockS();
    if (first_force_s < 0 && collector.has_force()) first_force_s = now_s;
    if (context.truth_expected && !collector.has_truth() && first_force_s >= 0 &&
        now_s - first_force_s >= options.truth_wait_s) {
      context.truth_expected = false;
      notice(fmt::format("birotor-monitor: no {} within {:.1f} s of the first FORCE: vehicle view from {} and {} only",
                         channels.truth, options.truth_wait_s, channels.force, channels.estimator_status));
    }
    const size_t clock_count = context.truth_expected ? collector.truth().size() : collector.forces().size();
    if (clock_count != last_clock_count) {
      last_clock_count = clock_count;
      last_arrival_s = now_s;
    }
    if (!collector.has_truth() && !collector.has_force() && now_s - start_s > options.startup_timeout_s) {
      timed_out = true;
      break;
    }
    if (now_s - last_view_s >= interval_s) {
      context.force_rate_hz = static_cast<double>(collector.forces().size() - last_view_forces) / (now_s - last_view_s);
      context.status_rate_hz =
          static_cast<double>(collector.status_messages() - last_view_status) / (now_s - last_view_s);
      last_view_forces = collector.forces().size();
      last_view_status = collector.status_messages();
      last_view_s = now_s;
      if (terminal) {
        if (view_drawn) std::printf("\x1b[%dA", kTerminalViewLines);
        std::fputs(TerminalView(collector, context).c_str(), stdout);
        view_drawn = true;
      } else if (!options.quiet) {
        std::printf("%s\n", PlainViewLine(collector, context).c_str());
      }
      std::fflush(stdout);
    }
    if (clock_count > 0) {
      if (options.duration_s > 0 && ElapsedS(collector) >= options.duration_s) break;
      if (options.until_sim_ends && now_s - last_arrival_s >= options.idle_s) break;
    }
  }
  lcm.reset();  // no more packets from here on
  if (terminal && view_drawn) {
    std::printf("\x1b[%dA", kTerminalViewLines);
    std::fputs(TerminalView(collector, context).c_str(), stdout);
  }
  if (timed_out) {
    return ReportError(fmt::format(
        "neither {} nor {} received on {} within {:.1f} s (are birotor-estimator and the vehicle or simulator "
        "running?)",
        channels.force, channels.truth, options.common.lcm_url, options.startup_timeout_s));
  }

  const std::string method = collector.has_status() ? collector.latest_status().method : std::string("unknown");
  std::printf("received: TRUTH %zu (gaps %lld), FORCE %zu, ESTIMATOR_STATUS %lld, decode errors %lld\n",
              collector.truth().size(), static_cast<long long>(collector.truth_gaps()), collector.forces().size(),
              static_cast<long long>(collector.status_messages()), static_cast<long long>(collector.decode_errors()));
  int exit_status = 0;  // an error below is reported, the rest of the summary still printed
  EvalResult result;
  if (collector.has_truth()) {
    result = collector.Evaluate(options.eval);
    std::printf("error figures (%s, %s; as birotor-eval):\n%s", label.c_str(), method.c_str(),
                SummaryText(result).c_str());
    if (options.markdown) {
      std::printf("%s%s", MarkdownTableHeader().c_str(), MarkdownTableRow(label, method, result).c_str());
    }
    if (result.paired == 0) {
      exit_status = ReportError("no FORCE message could be paired with TRUTH (is birotor-estimator running?)");
    }
  } else {
    std::printf("vehicle summary (%s, %s; no TRUTH, so no errors):\n%s", label.c_str(), method.c_str(),
                VehicleSummaryText(collector).c_str());
    if (!collector.has_force()) {
      exit_status = ReportError("no " + channels.force + " received (is birotor-estimator running?)");
    }
  }
  const std::string note = DeliveryNote(collector);
  if (!note.empty()) std::printf("note: %s\n", note.c_str());
  if (source->udp_counters() != nullptr) std::printf("input: %s\n", UdpCountersText(source->udp_counters()).c_str());
  std::fflush(stdout);

  if (!options.png.empty() && collector.has_force()) {
    ForcePlotOptions plot;
    plot.title = label + " - " + method + " (live)";
    plot.scale_lines = ThrustScaleLines(ekf);
    if (result.step_rotor != 0) {
      plot.markers.push_back(ThrustStepMarker(result.step_rotor, result.step_time_s));
    }
    if (WriteForcePlot(collector.forces(), collector.truth(), plot, options.png, &error)) {
      std::printf("plot: %s\n", options.png.c_str());
    } else {
      exit_status = ReportError("plot " + options.png + ": " + error);
    }
  }
  return exit_status;
}

}  // namespace
}  // namespace birotor

int main(int argc, char** argv) { return birotor::Main(argc, argv); }
