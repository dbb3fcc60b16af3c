// birotor-monitor: a compact live view of a running simulator and estimator
// (TRUTH, FORCE, ESTIMATOR_STATUS), and at the end the error figures of
// birotor-eval over every FORCE/TRUTH pair it received, plus an optional PNG.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "evaluation/eval_metrics.h"
#include "monitor/monitor_collector.h"
#include "monitor/monitor_view.h"
#include "plot/force_plot.h"
#include "simulator/scenario_yaml.h"
#include "transport/lcm_session.h"
#include "transport/logging.h"
#include "transport/program_options.h"
#include "transport/shutdown.h"

namespace birotor {
namespace {

struct MonitorOptions {
  CommonOptions common;
  std::string scenario_file;      // for the progress target and the table label; optional
  std::string label;              // scenario column of the table; default: scenario name or "live"
  double duration_s = 0;          // stop after this much vehicle time [s]; 0: no limit
  bool until_sim_ends = false;    // stop when TRUTH has been silent for idle_s
  double idle_s = 1.0;            // [s]
  double startup_timeout_s = 30;  // give up if no TRUTH arrives within this [s]
  double interval_s = 0;          // view refresh [s]; 0: 0.2 on a terminal, 1.0 otherwise
  bool plain = false;             // one plain line per refresh even on a terminal
  bool quiet = false;             // no live view, final figures only
  std::string png;                // plot file; empty: none
  bool markdown = false;          // print birotor-eval's Markdown table too
  EvalOptions eval;
};

double SteadyNowS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Raw subscription: hands every packet to the collector.
void OnPacket(const lcm::ReceiveBuffer* buffer, const std::string& channel, MonitorCollector* collector) {
  collector->HandlePacket(channel, buffer->data, buffer->data_size);
}

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
      "birotor-monitor: live view of TRUTH, FORCE and ESTIMATOR_STATUS, then the error "
      "figures of birotor-eval over what was received"};
  AddCommonOptions(app, &options.common);
  app.add_option("--scenario", options.scenario_file,
                 "Scenario file the simulator runs (progress target and table label)")
      ->check(CLI::ExistingFile);
  app.add_option("--label", options.label, "Scenario column of the table (default: scenario name or 'live')");
  app.add_option("--duration-s", options.duration_s, "Stop after this much vehicle time (0: no limit) [s]")
      ->check(CLI::Range(0.0, 1e6));
  app.add_flag("--until-sim-ends", options.until_sim_ends,
               "Stop when TRUTH has been silent for --idle-s after the first one");
  app.add_option("--idle-s", options.idle_s, "Silence that means the simulator ended [s]")
      ->check(CLI::Range(0.05, 60.0));
  app.add_option("--startup-timeout-s", options.startup_timeout_s, "Fail if no TRUTH arrives within this [s]")
      ->check(CLI::Range(0.1, 3600.0));
  app.add_option("--interval-s", options.interval_s, "View refresh period (0: 0.2 on a terminal, 1 otherwise) [s]")
      ->check(CLI::Range(0.0, 60.0));
  app.add_flag("--plain", options.plain, "One plain line per refresh, even on a terminal");
  app.add_flag("--quiet", options.quiet, "No live view; final figures only");
  app.add_option("--png", options.png, "Write the force plot (estimated vs true, errors) to this PNG");
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
      std::fprintf(stderr, "birotor-monitor: error: %s\n", e.what());
      return 1;
    }
  }
  if (label.empty()) label = "live";
  std::string error;
  if (!options.png.empty() && !CheckWritable(options.png, &error)) {
    std::fprintf(stderr, "birotor-monitor: error: %s\n", error.c_str());
    return 1;
  }

  std::unique_ptr<lcm::LCM> lcm = OpenLcm(options.common.lcm_url, &error);
  if (!lcm) {
    std::fprintf(stderr, "birotor-monitor: error: %s\n", error.c_str());
    return 1;
  }
  InstallShutdownHandlers();
  const ChannelNames channels = MakeChannelNames(options.common.prefix);
  MonitorCollector collector(channels, scenario_duration_s > 0 ? scenario_duration_s + 5.0 : 60.0);
  for (const std::string* channel : {&channels.truth, &channels.force, &channels.estimator_status}) {
    lcm->subscribeFunction(*channel, &OnPacket, &collector);
  }
  spdlog::info("birotor-monitor {} listening on {}: {} {} {}", BIROTOR_VERSION, options.common.lcm_url, channels.truth,
               channels.force, channels.estimator_status);
  if (options.duration_s <= 0 && !options.until_sim_ends) {
    spdlog::info("neither --duration-s nor --until-sim-ends: runs until SIGINT/SIGTERM");
  }

  const bool terminal = isatty(STDOUT_FILENO) && !options.plain && !options.quiet;
  const double interval_s = options.interval_s > 0 ? options.interval_s : (terminal ? 0.2 : 1.0);
  const double start_s = SteadyNowS();
  double last_truth_arrival_s = start_s;
  size_t last_truth_count = 0;
  double last_view_s = start_s;
  size_t last_view_forces = 0;
  bool view_drawn = false;
  bool timed_out = false;
  ViewContext context;
  context.scenario_duration_s = scenario_duration_s;

  while (!ShutdownRequested()) {
    if (HandleFor(*lcm, 0.05) < 0 && !ShutdownRequested() && errno != EINTR) {
      spdlog::error("lcm handle failed: {}; stopping", std::strerror(errno));
      break;
    }
    const double now_s = SteadyNowS();
    if (collector.truth().size() != last_truth_count) {
      last_truth_count = collector.truth().size();
      last_truth_arrival_s = now_s;
    }
    if (!collector.has_truth() && now_s - start_s > options.startup_timeout_s) {
      timed_out = true;
      break;
    }
    if (now_s - last_view_s >= interval_s) {
      context.force_rate_hz = static_cast<double>(collector.forces().size() - last_view_forces) / (now_s - last_view_s);
      last_view_forces = collector.forces().size();
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
    if (collector.has_truth()) {
      const double vehicle_s =
          static_cast<double>(collector.latest_truth().utime - collector.truth().front().utime) * 1e-6;
      if (options.duration_s > 0 && vehicle_s >= options.duration_s) break;
      if (options.until_sim_ends && now_s - last_truth_arrival_s >= options.idle_s) break;
    }
  }
  lcm.reset();  // no more packets from here on
  if (terminal && view_drawn) {
    std::printf("\x1b[%dA", kTerminalViewLines);
    std::fputs(TerminalView(collector, context).c_str(), stdout);
  }
  if (timed_out) {
    std::fprintf(stderr, "birotor-monitor: error: no %s received on %s within %.1f s (is the simulator running?)\n",
                 channels.truth.c_str(), options.common.lcm_url.c_str(), options.startup_timeout_s);
    return 1;
  }

  const EvalResult result = collector.Evaluate(options.eval);
  const MonitorHealth& health = collector.health();
  const std::string method = health.received ? health.method : std::string("unknown");
  std::printf("received: TRUTH %zu (gaps %lld), FORCE %zu, ESTIMATOR_STATUS %lld, decode errors %lld\n",
              collector.truth().size(), static_cast<long long>(collector.truth_gaps()), collector.forces().size(),
              static_cast<long long>(collector.status_messages()), static_cast<long long>(collector.decode_errors()));
  std::printf("error figures (%s, %s; as birotor-eval):\n%s", label.c_str(), method.c_str(),
              SummaryText(result).c_str());
  if (!collector.fault_utimes().empty() || collector.truth_gaps() > 0) {
    // Live UDP can drop packets on a busy machine; birotor-eval never does.
    std::printf(
        "note: %zu FORCE seq discontinuities or resets, %lld TRUTH gaps: input faults, or packets "
        "lost on the way to this monitor; the latter make the figures differ slightly from birotor-eval's\n",
        collector.fault_utimes().size(), static_cast<long long>(collector.truth_gaps()));
  }
  if (options.markdown) {
    std::printf("%s%s", MarkdownTableHeader().c_str(), MarkdownTableRow(label, method, result).c_str());
  }
  std::fflush(stdout);

  bool ok = true;
  if (result.paired == 0) {
    std::fprintf(
        stderr,
        "birotor-monitor: error: no FORCE message could be paired with TRUTH (is birotor-estimator running?)\n");
    ok = false;
  }
  if (!options.png.empty() && result.paired > 0) {
    if (WriteForcePlot(collector.forces(), collector.truth(), label + " - " + method + " (live)", options.png,
                       &error)) {
      std::printf("plot: %s\n", options.png.c_str());
    } else {
      std::fprintf(stderr, "birotor-monitor: error: plot %s: %s\n", options.png.c_str(), error.c_str());
      ok = false;
    }
  }
  return ok ? 0 : 1;
}

}  // namespace
}  // namespace birotor

int main(int argc, char** argv) { return birotor::Main(argc, argv); }
