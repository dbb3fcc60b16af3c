// birotor-replay: runs the estimator daemon's code over an LCM log as fast as
// possible and writes FORCE, ESTIMATOR_STATUS (vehicle-clock schedule) and
// TRUTH to an output log, optionally FORCE as CSV. Same log in, same bytes out.
#include <spdlog/spdlog.h>

#include <memory>
#include <string>

#include "params/estimator_config_yaml.h"
#include "params/yaml_reader.h"
#include "program/config_files.h"
#include "program/logging.h"
#include "program/program_options.h"
#include "replay/replayer.h"
#include "sinks/force_csv_sink.h"
#include "transport/host_clock.h"
#include "transport/output_file.h"

int main(int argc, char** argv) {
  using namespace birotor;
  CLI::App app{"birotor-replay: the estimator over an LCM log, as fast as possible"};
  CommonOptions common;
  AddCommonOptions(app, &common);
  app.remove_option(app.get_option("--lcm-url"));  // offline: reads files, never LCM (issue 24)
  std::string input_path, output_path, csv_path, method;
  std::string params_file = FindConfigFile("estimator.yaml");
  ReplayOptions options;
  app.add_option("--log", input_path, "Input LCM log (STRAIN, MOTOR, IMU, POSE, TRUTH)")->required();
  app.add_option("--output", output_path, "Output LCM log (FORCE, ESTIMATOR_STATUS, TRUTH)")->required();
  app.add_option("--csv", csv_path, "Also write FORCE as CSV");
  app.add_option("--params", params_file,
                 "Estimator parameter file; default: the " + ConfigSearchText("estimator.yaml"));
  app.add_option("--method", method, "Estimation method, overrides the file")
      ->check(CLI::IsMember(EstimationMethodNames()));
  app.add_option("--status-rate-hz", options.status_rate_hz, "ESTIMATOR_STATUS rate on the vehicle clock [Hz]")
      ->check(CLI::Range(0.1, 100.0));
  // Two callback flags, so --help shows no misleading {false} default.
  app.add_flag_callback(
      "--copy-truth", [&options] { options.copy_truth = true; }, "Copy TRUTH events to the output (the default)");
  app.add_flag_callback(
      "--no-copy-truth", [&options] { options.copy_truth = false; }, "Leave TRUTH events out of the output");
  double min_usable_fraction = kDefaultMinUsableLogFraction;
  app.add_option("--min-usable-fraction", min_usable_fraction,
                 "Refuse a log whose readable events are less than this share of its bytes")
      ->check(CLI::Range(0.0, 1.0));
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-replay", common.log_level);
  options.prefix = common.prefix;

  EstimatorConfig config;
  try {
    config = LoadEstimatorConfig(params_file);
  } catch (const std::exception& error) {
    return ReportError(error.what());
  }
  if (!method.empty()) config.method = method;

  std::string error;
  // An output never overwrites an input, and outputs go to temporary files
  // renamed only when everything was written (transport/output_file.h).
  if (!CheckOutputs({output_path, csv_path}, {input_path, params_file}, &error)) return ReportError(error);
  LogWriter writer;
  if (!writer.Open(output_path, &error)) {
    return ReportError(error);
  }
  LogSink log_sink(&writer);
  OutputFile csv;
  if (!csv_path.empty() && !csv.Open(csv_path, &error)) return ReportError(error);
  std::unique_ptr<ForceCsvSink> csv_sink;
  MessageSink* sink = &log_sink;
  if (csv.is_open()) {
    csv_sink = std::make_unique<ForceCsvSink>(csv.stream(), MakeChannelNames(common.prefix).force, &log_sink);
    sink = csv_sink.get();
  }

  const Stopwatch stopwatch;
  Replayer replayer(config, options, sink);
  std::string damage;
  if (!ReplayLogFile(input_path, &replayer, &damage, &error, min_usable_fraction)) {
    return ReportError(error);  // writer and csv are abandoned: no output file is left
  }
  if (!damage.empty()) spdlog::warn("{}", damage);
  if (replayer.stats().input_packets == 0 || replayer.stats().forces == 0) {
    return ReportError(fmt::format("{}: {} events but no {} input produced a FORCE estimate", input_path,
                                   replayer.stats().events, common.prefix));
  }
  const double wall_s = stopwatch.ElapsedS();
  if (log_sink.failed()) return ReportError("writing " + output_path + " failed");
  if (csv.is_open() && !csv.Commit(&error)) return ReportError(error);
  if (!writer.Close()) return ReportError(writer.error());

  const ReplayStats& stats = replayer.stats();
  const double log_s =
      stats.last_utime > stats.first_utime ? static_cast<double>(stats.last_utime - stats.first_utime) * 1e-6 : 0.0;
  const PipelineHealth& health = replayer.service().health();
  spdlog::info("method {}: {} events, {} FORCE, {} status, {} TRUTH; resets {}", config.method, stats.events,
               stats.forces, replayer.service().status_published(), stats.truth_copied, health.resets);
  spdlog::info("{:.3f} s of log in {:.3f} s wall: {:.0f}x real time", log_s, wall_s, wall_s > 0 ? log_s / wall_s : 0.0);
  return 0;
}
