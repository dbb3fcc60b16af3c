// birotor-plot: PNG of a log holding FORCE (the output of birotor-replay or a
// flight): estimated rotor forces with 1 sigma, against TRUTH and with the
// error when the log has it, thrust efficiency with the fault threshold, and
// the status flags with their first times (plot/force_plot.h).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <string>

#include "evaluation/eval_metrics.h"
#include "evaluation/eval_runner.h"
#include "params/estimator_config_yaml.h"
#include "plot/force_plot.h"
#include "program/logging.h"
#include "program/program_options.h"
#include "transport/log_io.h"
#include "transport/output_file.h"

int main(int argc, char** argv) {
  using namespace birotor;
  CLI::App app{"birotor-plot: estimated (and true) rotor force, thrust efficiency and flags (thesis figures 5.1, 5.2)"};
  CommonOptions common;
  AddCommonOptions(app, &common);
  app.remove_option(app.get_option("--lcm-url"));  // offline: reads files, never LCM (issue 24)
  std::string log_path, png_path;
  ForcePlotOptions plot;
  app.add_option("--log", log_path, "LCM log with FORCE, and TRUTH if simulated (birotor-replay output)")->required();
  app.add_option("--png", png_path, "PNG file to write (temporary file + rename)")->required();
  app.add_option("--title", plot.title, "Plot title (default: what the plot shows and the log's file name)");
  std::string params_file;
  app.add_option("--params", params_file,
                 "Estimator parameter file of the run, for its fault thresholds (default: the built-in defaults)");
  double min_usable_fraction = kDefaultMinUsableLogFraction;
  app.add_option("--min-usable-fraction", min_usable_fraction,
                 "Refuse a log whose readable events are less than this share of its bytes")
      ->check(CLI::Range(0.0, 1.0));
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-plot", common.log_level);

  if (!params_file.empty()) {
    try {
      plot.scale_lines = ThrustScaleLines(LoadEstimatorConfig(params_file).ekf);
    } catch (const std::exception& e) {
      return ReportError(e.what());
    }
  }
  const ChannelNames channels = MakeChannelNames(common.prefix);
  ForceTruthCollector collector(channels);
  LogReader reader;
  std::string error;
  if (!CheckOutputs({png_path}, {log_path, params_file}, &error) || !reader.Open(log_path, &error)) {
    return ReportError(error);
  }
  LogEvent event;
  while (reader.Next(&event)) {
    collector.Publish(event.channel, event.timestamp_us, event.data.data(), event.data.size());
  }
  std::string damage;
  if (!CheckLogUsable(reader, log_path, min_usable_fraction, &error, &damage)) {
    return ReportError(error);
  }
  if (!damage.empty()) spdlog::warn("{}", damage);
  if (plot.title.empty()) plot.title = ForcePlotTitle(log_path);
  if (!collector.truth.empty()) {
    const EvalResult result = Evaluate(collector.forces, collector.truth, {}, EvalOptions{});
    if (result.step_rotor != 0) plot.markers.push_back(ThrustStepMarker(result.step_rotor, result.step_time_s));
  }
  if (!WriteForcePlot(collector.forces, collector.truth, plot, png_path, &error)) {
    return ReportError(error);
  }
  std::printf("%s: %zu estimates, %zu truth samples\n", png_path.c_str(), collector.forces.size(),
              collector.truth.size());
  return 0;
}
