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

void AddMonitorOptions(CLI::App& app, MonitorOptions* options) {
  AddCommonOptions(app, &options->common);
  app.add_option("--scenario", options->scenario_file,
                 "Scenario file the simulator runs (progress target and table label)");
  app.add_option("--label", options->label, "Scenario column of the table (default: scenario name or 'live')");
  app.add_option("--duration-s", options->duration_s, "Stop after this much vehicle time (0: no limit) [s]")
      ->check(CLI::Range(0.0, 1e6));
  app.add_flag("--until-sim-ends", options->until_sim_ends,
               "Stop when TRUTH (FORCE without truth) has been silent for --idle-s after the first one");
  app.add_option("--idle-s", options->idle_s, "Silence that means the simulator (or vehicle) stopped [s]")
      ->check(CLI::Range(0.05, 60.0));
  app.add_option("--startup-timeout-s", options->startup_timeout_s,
                 "Fail if neither TRUTH nor FORCE arrives within this [s]")
      ->check(CLI::Range(0.1, 3600.0));
  app.add_flag("--no-truth", options->no_truth,
               "Vehicle view: FORCE and ESTIMATOR_STATUS only, never wait for TRUTH (a real vehicle)");
  app.add_option("--truth-wait-s", options->truth_wait_s,
                 "FORCE arrives but no TRUTH within this: switch to the vehicle view, said on screen [s]")
      ->check(CLI::Range(0.1, 3600.0));
  app.add_option("--stale-age-s", options->stale_age_s,
                 "Show an input as STALE when its newest sample is older than this (vehicle clock) [s]")
      ->check(CLI::Range(1e-3, 3600.0));
  app.add_option("--params", options->params_file,
                 "Estimator parameter file the daemon runs, for its fault thresholds in the view and plot "
                 "(default: the built-in estimator defaults)");
  app.add_option("--interval-s", options->interval_s, "View refresh period (0: 0.2 on a terminal, 1 otherwise) [s]")
      ->check(CLI::Range(0.0, 60.0));
  app.add_flag("--plain", options->plain, "One plain line per refresh, even on a terminal");
  app.add_flag("--quiet", options->quiet, "No live view; final figures only");
  app.add_option("--png", options->png,
                 "Write the force plot (estimates with 1 sigma, truth, errors, thrust efficiency, flags) to this PNG");
  app.add_flag("--markdown", options->markdown, "Also print the figures as birotor-eval's Markdown table");
  app.add_option("--warmup-s", options->eval.warmup_s, "Unscored start-up time, as birotor-eval [s]")
      ->check(CLI::Range(0.0, 100.0));
}

// What the files give the run: the progress target, the table label and the
// estimator's thresholds.
struct MonitorSetup {
  double scenario_duration_s = 0;  // [s]; 0: unknown
  std::string label;
  EkfOptions ekf;
};

// Reads --scenario and --params and checks that --png can be written.
bool LoadSetup(const MonitorOptions& options, MonitorSetup* setup, std::string* error) {
  setup->scenario_duration_s = options.duration_s;
  setup->label = options.label;
  try {
    if (!options.scenario_file.empty()) {
      const Scenario scenario = LoadScenario(options.scenario_file);
      if (setup->scenario_duration_s <= 0) setup->scenario_duration_s = scenario.duration_s;
      if (setup->label.empty()) setup->label = scenario.name;
    }
    if (setup->label.empty()) setup->label = "live";
    if (!options.params_file.empty()) setup->ekf = LoadEstimatorConfig(options.params_file).ekf;
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
  return options.png.empty() || CheckWritable(options.png, error);
}

// The live part: receive, switch to the vehicle view when TRUTH does not
// come, redraw the view every interval, stop on duration, idle or signal.
class LiveView {
 public:
  LiveView(const MonitorOptions& options, const MonitorSetup& setup, const ChannelNames& channels)
      : options_(options),
        channels_(channels),
        terminal_(isatty(STDOUT_FILENO) && !options.plain && !options.quiet),
        interval_s_(options.interval_s > 0 ? options.interval_s : (terminal_ ? 0.2 : 1.0)),
        start_s_(SteadyClockS()),
        last_arrival_s_(start_s_),
        last_view_s_(start_s_) {
    context_.scenario_duration_s = setup.scenario_duration_s;
    context_.truth_expected = !options.no_truth;
    context_.stale_age_s = options.stale_age_s;
    context_.thresholds = ThresholdWords(ThrustScaleLines(setup.ekf));
  }

  // Runs until a stop condition; false if nothing arrived within --startup-timeout-s.
  bool Run(MessageSource* source, const MonitorCollector& collector) {
    if (options_.no_truth) Notice("birotor-monitor: vehicle view (--no-truth): FORCE and ESTIMATOR_STATUS only");
    DroppedDatagramLog dropped;
    while (!ShutdownRequested()) {
      ReceiveUntil(source, 0.05, SteadyClockUs() + 50000);
      if (source->finished()) {
        spdlog::error("{}; stopping", source->error());
        break;
      }
      dropped.Check(source->udp_counters());
      const double now_s = SteadyClockS();
      const size_t clock_count = Track(collector, now_s);
      if (!collector.has_truth() && !collector.has_force() && now_s - start_s_ > options_.startup_timeout_s) {
        return false;
      }
      if (now_s - last_view_s_ >= interval_s_) Draw(collector, now_s);
      if (clock_count > 0) {
        if (options_.duration_s > 0 && ElapsedS(collector) >= options_.duration_s) break;
        if (options_.until_sim_ends && now_s - last_arrival_s_ >= options_.idle_s) break;
      }
    }
    return true;
  }

  // The terminal view once more with the final state.
  void Finish(const MonitorCollector& collector) {
    if (!terminal_ || !view_drawn_) return;
    std::printf("\x1b[%dA", kTerminalViewLines);
    std::fputs(TerminalView(collector, context_).c_str(), stdout);
  }

 private:
  // A notice printed once above the live view (it scrolls with plain lines).
  void Notice(const std::string& text) {
    if (options_.quiet) return;
    if (terminal_ && view_drawn_) std::printf("\x1b[%dA", kTerminalViewLines);
    std::printf("%s%s\n", terminal_ ? "\x1b[K" : "", text.c_str());
    view_drawn_ = false;  // the view is drawn again below the notice
    std::fflush(stdout);
  }

  // The vehicle-view switch and the arrivals of the clock stream (TRUTH, or
  // FORCE without truth); returns that stream's count.
  size_t Track(const MonitorCollector& collector, double now_s) {
    if (first_force_s_ < 0 && collector.has_force()) first_force_s_ = now_s;
    if (context_.truth_expected && !collector.has_truth() && first_force_s_ >= 0 &&
        now_s - first_force_s_ >= options_.truth_wait_s) {
      context_.truth_expected = false;
      Notice(fmt::format("birotor-monitor: no {} within {:.1f} s of the first FORCE: vehicle view from {} and {} only",
                         channels_.truth, options_.truth_wait_s, channels_.force, channels_.estimator_status));
    }
    const size_t clock_count = context_.truth_expected ? collector.truth().size() : collector.forces().size();
    if (clock_count != last_clock_count_) {
      last_clock_count_ = clock_count;
      last_arrival_s_ = now_s;
    }
    return clock_count;
  }

  // The rates since the last view, then the view.
  void Draw(const MonitorCollector& collector, double now_s) {
    context_.force_rate_hz =
        static_cast<double>(collector.forces().size() - last_view_forces_) / (now_s - last_view_s_);
    context_.status_rate_hz =
        static_cast<double>(collector.status_messages() - last_view_status_) / (now_s - last_view_s_);
    last_view_forces_ = collector.forces().size();
    last_view_status_ = collector.status_messages();
    last_view_s_ = now_s;
    if (terminal_) {
      if (view_drawn_) std::printf("\x1b[%dA", kTerminalViewLines);
      std::fputs(TerminalView(collector, context_).c_str(), stdout);
      view_drawn_ = true;
    } else if (!options_.quiet) {
      std::printf("%s\n", PlainViewLine(collector, context_).c_str());
    }
    std::fflush(stdout);
  }

  const MonitorOptions& options_;
  const ChannelNames& channels_;
  const bool terminal_;
  const double interval_s_;
  const double start_s_;
  double last_arrival_s_;  // of the clock stream: TRUTH, or FORCE without truth
  size_t last_clock_count_ = 0;
  double first_force_s_ = -1;
  double last_view_s_;
  size_t last_view_forces_ = 0;
  int64_t last_view_status_ = 0;
  bool view_drawn_ = false;
  ViewContext context_;
};

// The final figures (with TRUTH) or the vehicle summary (without), the
// delivery note and the input counters; returns the exit status.
int PrintSummary(const MonitorOptions& options, const MonitorSetup& setup, const ChannelNames& channels,
                 const MonitorCollector& collector, const MessageSource& source, const std::string& method,
                 EvalResult* result) {
  std::printf("received: TRUTH %zu (gaps %lld), FORCE %zu, ESTIMATOR_STATUS %lld, decode errors %lld\n",
              collector.truth().size(), static_cast<long long>(collector.truth_gaps()), collector.forces().size(),
              static_cast<long long>(collector.status_messages()), static_cast<long long>(collector.decode_errors()));
  int exit_status = 0;  // an error below is reported, the rest of the summary still printed
  if (collector.has_truth()) {
    *result = collector.Evaluate(options.eval);
    std::printf("error figures (%s, %s; as birotor-eval):\n%s", setup.label.c_str(), method.c_str(),
                SummaryText(*result).c_str());
    if (options.markdown) {
      std::printf("%s%s", MarkdownTableHeader().c_str(), MarkdownTableRow(setup.label, method, *result).c_str());
    }
    if (result->paired == 0) {
      exit_status = ReportError("no FORCE message could be paired with TRUTH (is birotor-estimator running?)");
    }
  } else {
    std::printf("vehicle summary (%s, %s; no TRUTH, so no errors):\n%s", setup.label.c_str(), method.c_str(),
                VehicleSummaryText(collector).c_str());
    if (!collector.has_force()) {
      exit_status = ReportError("no " + channels.force + " received (is birotor-estimator running?)");
    }
  }
  const std::string note = DeliveryNote(collector);
  if (!note.empty()) std::printf("note: %s\n", note.c_str());
  if (source.udp_counters() != nullptr) std::printf("input: %s\n", UdpCountersText(source.udp_counters()).c_str());
  std::fflush(stdout);
  return exit_status;
}

// --png: the force plot of what was received; false (reported) if it fails.
bool WritePlot(const MonitorOptions& options, const MonitorSetup& setup, const MonitorCollector& collector,
               const std::string& method, const EvalResult& result) {
  ForcePlotOptions plot;
  plot.title = setup.label + " - " + method + " (live)";
  plot.scale_lines = ThrustScaleLines(setup.ekf);
  if (result.step_rotor != 0) {
    plot.markers.push_back(ThrustStepMarker(result.step_rotor, result.step_time_s));
  }
  std::string error;
  if (!WriteForcePlot(collector.forces(), collector.truth(), plot, options.png, &error)) {
    ReportError("plot " + options.png + ": " + error);
    return false;
  }
  std::printf("plot: %s\n", options.png.c_str());
  return true;
}

int Main(int argc, char** argv) {
  MonitorOptions options;
  CLI::App app{
      "birotor-monitor: live view of FORCE and ESTIMATOR_STATUS (and TRUTH from a simulator), then the error "
      "figures of birotor-eval over what was received, or without TRUTH a summary of the estimates and health"};
  AddMonitorOptions(app, &options);
  if (const std::optional<int> exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-monitor", options.common.log_level);
  MonitorSetup setup;
  std::string error;
  if (!LoadSetup(options, &setup, &error)) return ReportError(error);

  std::unique_ptr<lcm::LCM> lcm = OpenLcm(options.common.lcm_url, &error);
  if (!lcm) return ReportError(error);
  InstallShutdownHandlers();
  const ChannelNames channels = MakeChannelNames(options.common.prefix);
  MonitorCollector collector(channels, setup.scenario_duration_s > 0 ? setup.scenario_duration_s + 5.0 : 60.0);
  // Inputs through the shared message source: on udpm our own LC02 reader,
  // which drops and counts fragments instead of reassembling them.
  std::unique_ptr<MessageSource> source = OpenLiveSource(options.common.lcm_url, lcm.get(), &error);
  if (!source || !source->Subscribe(collector.InputChannels(), &collector, &error)) return ReportError(error);
  spdlog::info("birotor-monitor {} listening on {} ({}): {} {} {}", BIROTOR_VERSION, options.common.lcm_url,
               source->Describe(), channels.truth, channels.force, channels.estimator_status);
  if (options.duration_s <= 0 && !options.until_sim_ends) {
    spdlog::info("neither --duration-s nor --until-sim-ends: runs until SIGINT/SIGTERM");
  }

  LiveView view(options, setup, channels);
  const bool received = view.Run(source.get(), collector);
  lcm.reset();  // no more packets from here on
  view.Finish(collector);
  if (!received) {
    return ReportError(fmt::format(
        "neither {} nor {} received on {} within {:.1f} s (are birotor-estimator and the vehicle or simulator "
        "running?)",
        channels.force, channels.truth, options.common.lcm_url, options.startup_timeout_s));
  }
  const std::string method = collector.has_status() ? collector.latest_status().method : std::string("unknown");
  EvalResult result;
  int exit_status = PrintSummary(options, setup, channels, collector, *source, method, &result);
  if (!options.png.empty() && collector.has_force() && !WritePlot(options, setup, collector, method, result)) {
    exit_status = kExitFailure;
  }
  return exit_status;
}

}  // namespace
}  // namespace birotor

int main(int argc, char** argv) { return birotor::Main(argc, argv); }
