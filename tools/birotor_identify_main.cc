// birotor-identify: reads lcm-logger files (bench or flight), identifies c_T,
// tau_m, k, d and the deflection-force maps with Ceres, and writes the
// parameter file the estimator and simulator load, plus a readable report.
#include <spdlog/spdlog.h>

#include <string>
#include <vector>

#include "identification/identify.h"
#include "identification/parameter_file.h"
#include "params/vehicle_params_yaml.h"
#include "plot/fit_plot.h"
#include "replay/identification_log_loader.h"
#include "transport/config_files.h"
#include "transport/host_clock.h"
#include "transport/log_io.h"
#include "transport/logging.h"
#include "transport/output_file.h"
#include "transport/program_options.h"

namespace {

struct IdentifyOptions {
  std::vector<std::string> logs;
  std::string mode = "auto";
  std::string params = birotor::FindConfigFile("reference_vehicle.yaml");
  std::string config;  // optional file with an `identification:` section
  std::string output;
  std::string report;
  std::string plot;
  double min_usable_fraction = birotor::kDefaultMinUsableLogFraction;
};

}  // namespace

int main(int argc, char** argv) {
  using namespace birotor;
  CommonOptions common;
  IdentifyOptions cli;
  CLI::App app("Identify the birotor's c_T, tau_m, k, d and deflection-force maps from LCM logs", "birotor-identify");
  AddCommonOptions(app, &common);
  app.add_option("--log", cli.logs, "LCM log file (repeat for several)")->required()->check(CLI::ExistingFile);
  app.add_option("--mode", cli.mode, "bench (load cells), flight, or auto (bench if every log has load cells)")
      ->check(CLI::IsMember({"auto", "bench", "flight"}));
  app.add_option("--params", cli.params,
                 "Base parameter file (complete vehicle: section): masses, lengths, inertia are taken as known; "
                 "default: the " +
                     ConfigSearchText("reference_vehicle.yaml"));
  app.add_option("--config", cli.config,
                 "YAML file with a complete `identification:` section of options (the shipped identification.yaml "
                 "has every key at its default); none: the built-in defaults");
  app.add_option("--output", cli.output, "Identified parameter file (written atomically)")->required();
  app.add_option("--report", cli.report, "Readable report (Markdown)");
  app.add_option("--plot", cli.plot, "PNG of fit versus data (needs gnuplot)");
  app.add_option("--min-usable-fraction", cli.min_usable_fraction,
                 "Refuse a log whose readable events are less than this share of its bytes")
      ->check(CLI::Range(0.0, 1.0));
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-identify", common.log_level);

  VehicleParams base;
  IdentificationOptions options;
  try {
    base = LoadVehicleParams(cli.params);
    if (!cli.config.empty()) options = LoadIdentificationOptions(cli.config);
  } catch (const ParamError& e) {
    return ReportError(e.what());
  }
  spdlog::info("base parameters {} (checksum {})", cli.params, FileChecksum(cli.params));
  // Outputs: never an input, each through a temporary file renamed at the
  // end; opened now so an unwritable folder is refused before the fit.
  std::string error;
  std::vector<std::string> inputs = cli.logs;
  inputs.push_back(cli.params);
  inputs.push_back(cli.config);
  OutputFile output, report;
  if (!CheckOutputs({cli.output, cli.report, cli.plot}, inputs, &error) || !output.Open(cli.output, &error) ||
      (!cli.report.empty() && !report.Open(cli.report, &error))) {
    return ReportError(error);
  }

  const Stopwatch stopwatch;
  std::vector<SensorLog> logs;
  for (const std::string& path : cli.logs) {
    SensorLog log;
    LogLoadReport load;
    if (!LoadSensorLog(path, common.prefix, &log, &load, &error, cli.min_usable_fraction)) return ReportError(error);
    if (!load.damage.empty()) spdlog::warn("{}", load.damage);
    if (load.decode_errors > 0) spdlog::warn("{}: {} events did not decode and were skipped", path, load.decode_errors);
    spdlog::info("{}: {} strain, {} motor, {} imu, {} loadcell samples", path, log.strain.size(), log.motor.size(),
                 log.imu.size(), log.loadcell.size());
    logs.push_back(std::move(log));
  }
  const IdentificationMode mode = cli.mode == "bench"    ? IdentificationMode::kBench
                                  : cli.mode == "flight" ? IdentificationMode::kFlight
                                                         : IdentificationMode::kAuto;
  const IdentificationResult result = Identify(std::move(logs), base, options, mode);
  const double elapsed_s = stopwatch.ElapsedS();
  if (result.dropped.total() > 0) {
    spdlog::warn("bad samples (non-finite, bad stamp, out of order, duplicate): {}", result.dropped.Summary());
  }

  if (report.is_open()) {
    report.Write(IdentificationReport(result));
    if (!report.Commit(&error)) return ReportError(error);
  }
  if (!result.ok) {
    std::string reasons;
    for (const std::string& e : result.errors) reasons += (reasons.empty() ? "" : "; ") + e;
    return ReportError("identification refused (" + result.mode + " mode), no parameter file written: " + reasons);
  }
  for (const std::string& w : result.warnings) spdlog::warn("{}", w);
  for (const ParameterEstimate& e : result.estimates) {
    if (e.determined) {
      spdlog::info("{:6s} = {:.6g} +- {:.3g} ({:.3f} %)", e.symbol, e.value, e.sigma, 100.0 * e.sigma / e.value);
    } else {
      spdlog::warn("{:6s} NOT DETERMINED by these logs: {} keeps the base file's value, marked so in {}", e.symbol,
                   e.key, cli.output);
    }
  }
  for (const DeflectionForceMap& m : result.maps) {
    spdlog::info("arm {} map: {} coefficients, residual RMS {:.4f} N", m.arm + 1, m.coefficients.size(),
                 m.residual_rms_n);
  }
  output.Write(IdentifiedParameterYaml(result));
  if (!output.Commit(&error)) return ReportError(error);
  // A failed plot is an error (exit 1), but the parameter file stands.
  if (!cli.plot.empty()) {
    if (!WriteFitPlot(result.plots, "birotor-identify (" + result.mode + " mode): fit versus data", cli.plot, &error)) {
      return ReportError("--plot " + cli.plot + ": " + error);
    }
    spdlog::info("wrote {}", cli.plot);
  }
  spdlog::info("wrote {} ({} mode, {:.2f} s)", cli.output, result.mode, elapsed_s);
  return 0;
}
