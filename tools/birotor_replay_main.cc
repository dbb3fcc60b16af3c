// birotor-replay: runs the estimator daemon's code over an LCM log as fast as
// possible and writes FORCE, ESTIMATOR_STATUS (vehicle-clock schedule) with
// ESTIMATOR_LEARNED_N, and TRUTH to an output log, optionally FORCE as CSV.
// Same log in, same bytes out.
#include <spdlog/spdlog.h>

#include <memory>
#include <string>

#include "params/estimator_config_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "params/yaml_reader.h"
#include "program/config_files.h"
#include "program/logging.h"
#include "program/program_options.h"
#include "replay/replayer.h"
#include "sinks/force_csv_sink.h"
#include "transport/host_clock.h"
#include "transport/output_file.h"

namespace birotor {
namespace {

struct ReplayCli {
  CommonOptions common;
  std::string input_path, output_path, csv_path;
  std::string params_file = FindConfigFile("estimator.yaml");
  std::string method;        // overrides the file's; empty: the file's
  std::string vehicle_file;  // --vehicle: a description with N arms, the counted channels
  ReplayOptions options;
  double min_usable_fraction = kDefaultMinUsableLogFraction;
};

void AddReplayOptions(CLI::App& app, ReplayCli* cli) {
  AddCommonOptions(app, &cli->common);
  app.remove_option(app.get_option("--lcm-url"));  // offline: reads files, never LCM (issue 24)
  app.add_option("--log", cli->input_path, "Input LCM log (STRAIN, MOTOR, IMU, POSE, TRUTH)")->required();
  app.add_option("--output", cli->output_path, "Output LCM log (FORCE, ESTIMATOR_STATUS, ESTIMATOR_LEARNED_N, TRUTH)")
      ->required();
  app.add_option("--csv", cli->csv_path, "Also write FORCE as CSV");
  app.add_option("--params", cli->params_file,
                 "Estimator parameter file; default: the " + ConfigSearchText("estimator.yaml"));
  app.add_option("--method", cli->method, "Estimation method, overrides the file")
      ->check(CLI::IsMember(EstimationMethodNames()));
  app.add_option("--vehicle", cli->vehicle_file,
                 "A vehicle description with N arms (e.g. config/vehicles/trirotor.yaml): the N-arm EKF over the "
                 "log's STRAIN_N, MOTOR_N, IMU and POSE, FORCE_N out (birotor-sim --vehicle writes such logs)")
      ->check(CLI::ExistingFile);
  app.add_option("--status-rate-hz", cli->options.status_rate_hz, "ESTIMATOR_STATUS rate on the vehicle clock [Hz]")
      ->check(CLI::Range(0.1, 100.0));
  // Two callback flags, so --help shows no misleading {false} default.
  ReplayOptions* options = &cli->options;
  app.add_flag_callback(
      "--copy-truth", [options] { options->copy_truth = true; }, "Copy TRUTH events to the output (the default)");
  app.add_flag_callback(
      "--no-copy-truth", [options] { options->copy_truth = false; }, "Leave TRUTH events out of the output");
  app.add_option("--min-usable-fraction", cli->min_usable_fraction,
                 "Refuse a log whose readable events are less than this share of its bytes")
      ->check(CLI::Range(0.0, 1.0));
}

// The output log and, with --csv, the FORCE CSV in front of it. An output
// never overwrites an input, and outputs go to temporary files renamed only
// when everything was written (transport/output_file.h).
class ReplayOutputs {
 public:
  ReplayOutputs() : log_sink_(&writer_) {}

  bool Open(const ReplayCli& cli, std::string* error) {
    if (!CheckOutputs({cli.output_path, cli.csv_path}, {cli.input_path, cli.params_file}, error) ||
        !writer_.Open(cli.output_path, error) || (!cli.csv_path.empty() && !csv_.Open(cli.csv_path, error))) {
      return false;
    }
    if (csv_.is_open()) {
      csv_sink_ = std::make_unique<ForceCsvSink>(csv_.stream(), MakeChannelNames(cli.common.prefix).force, &log_sink_);
    }
    return true;
  }
  MessageSink* sink() { return csv_sink_ ? static_cast<MessageSink*>(csv_sink_.get()) : &log_sink_; }

  // Renames the outputs into place; an error message, empty on success.
  std::string Commit(const std::string& output_path) {
    std::string error;
    if (log_sink_.failed()) return "writing " + output_path + " failed";
    if (csv_.is_open() && !csv_.Commit(&error)) return error;
    if (!writer_.Close()) return writer_.error();
    return "";
  }

 private:
  LogWriter writer_;
  LogSink log_sink_;
  OutputFile csv_;
  std::unique_ptr<ForceCsvSink> csv_sink_;
};

template <class Replayer>
void LogReplayed(const Replayer& replayer, const std::string& method, double wall_s) {
  const ReplayStats& stats = replayer.stats();
  const double log_s =
      stats.last_utime > stats.first_utime ? static_cast<double>(stats.last_utime - stats.first_utime) * 1e-6 : 0.0;
  spdlog::info("method {}: {} events, {} FORCE, {} status, {} TRUTH; resets {}", method, stats.events, stats.forces,
               replayer.service().status_published(), stats.truth_copied, replayer.service().health().resets);
  spdlog::info("{:.3f} s of log in {:.3f} s wall: {:.0f}x real time", log_s, wall_s, wall_s > 0 ? log_s / wall_s : 0.0);
}

// Replays the log through replayer into the outputs; the exit status.
template <class Replayer>
int Replay(const ReplayCli& cli, const std::string& method, Replayer* replayer, ReplayOutputs* outputs) {
  const Stopwatch stopwatch;
  std::string damage, error;
  if (!ReplayLogFile(cli.input_path, replayer, &damage, &error, cli.min_usable_fraction)) {
    return ReportError(error);  // the outputs are abandoned: no output file is left
  }
  if (!damage.empty()) spdlog::warn("{}", damage);
  const ReplayStats& stats = replayer->stats();
  if (stats.input_packets == 0 || stats.forces == 0) {
    return ReportError(fmt::format("{}: {} events but no {} input produced a FORCE{} estimate", cli.input_path,
                                   stats.events, cli.common.prefix, cli.vehicle_file.empty() ? "" : "_N"));
  }
  const double wall_s = stopwatch.ElapsedS();
  if (!(error = outputs->Commit(cli.output_path)).empty()) return ReportError(error);
  LogReplayed(*replayer, method, wall_s);
  return 0;
}

}  // namespace
}  // namespace birotor

int main(int argc, char** argv) {
  using namespace birotor;
  CLI::App app{"birotor-replay: the estimator over an LCM log, as fast as possible"};
  ReplayCli cli;
  AddReplayOptions(app, &cli);
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-replay", cli.common.log_level);
  cli.options.prefix = cli.common.prefix;

  EstimatorConfig config;
  try {
    config = LoadEstimatorConfig(cli.params_file);
  } catch (const std::exception& error) {
    return ReportError(error.what());
  }
  if (!cli.method.empty()) config.method = cli.method;
  std::string error;
  ReplayOutputs outputs;
  if (!outputs.Open(cli, &error)) return ReportError(error);

  if (cli.vehicle_file.empty()) {
    Replayer replayer(config, cli.options, outputs.sink());
    return Replay(cli, config.method, &replayer, &outputs);
  }
  try {
    config.vehicle = LoadVehicleDescription(cli.vehicle_file);
    MultiArmReplayer replayer(config, cli.options, outputs.sink());
    return Replay(cli, config.method + " (N arms)", &replayer, &outputs);
  } catch (const std::exception& e) {
    return ReportError(e.what());
  }
}
