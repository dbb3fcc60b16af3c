// birotor-identify: reads lcm-logger files (bench or flight), identifies c_T,
// tau_m, k, d and the deflection-force maps with Ceres, and writes the
// parameter file the estimator and simulator load, plus a readable report.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <string>
#include <vector>

#include "identification/identify.h"
#include "identification/parameter_file.h"
#include "params/vehicle_params_yaml.h"
#include "plot/fit_plot.h"
#include "replay/identification_log_loader.h"
#include "transport/host_clock.h"
#include "transport/log_io.h"
#include "transport/logging.h"
#include "transport/output_file.h"
#include "transport/program_options.h"

namespace {

constexpr int kExitFailure = 1;

// One line "birotor-identify: error: ..." and the failure exit status.
int Fail(const std::string& message) {
  std::fprintf(stderr, "birotor-identify: error: %s\n", message.c_str());
  return kExitFailure;
}

struct IdentifyOptions {
  std::vector<std::string> logs;
  std::string mode = "auto";
  std::string params = std::string(BIROTOR_SOURCE_DIR) + "/config/reference_vehicle.yaml";
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
  app.add_option("--params", cli.params, "Base parameter file: masses, lengths, inertia are taken as known");
  app.add_option("--config", cli.config, "Optional YAML file with an `identification:` section of options");
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
    if (!cli.config.empty()) {
      YamlSection root = YamlSection::LoadFile(cli.config);
      ReadIdentificationOptions(root.Section("identification"), &options);
    }
  } catch (const ParamError& e) {
    return Fail(e.what());
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
    return Fail(error);
  }

  const Stopwatch stopwatch;
  std::vector<SensorLog> logs;
  for (const std::string& path : cli.logs) {
    SensorLog log;
    LogLoadReport load;
    if (!LoadSensorLog(path, common.prefix, &log, &load, &error, cli.min_usable_fraction)) return Fail(error);
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
    if (!report.Commit(&error)) return Fail(error);
  }
  if (!result.ok) {
    std::string missing;
    for (const std::string& e : result.errors) missing += (missing.empty() ? "" : "; ") + e;
    return Fail("identification refused (" + result.mode + " mode), the data lacks what is needed: " + missing);
  }
  for (const std::string& w : result.warnings) spdlog::warn("{}", w);
  for (const ParameterEstimate& e : result.estimates) {
    spdlog::info("{:6s} = {:.6g} +- {:.3g} ({:.3f} %){}", e.symbol, e.value, e.sigma, 100.0 * e.sigma / e.value,
                 e.determined ? "" : " NOT DETERMINED, base value kept");
  }
  for (const DeflectionForceMap& m : result.maps) {
    spdlog::info("arm {} map: {} coefficients, residual RMS {:.4f} N", m.arm + 1, m.coefficients.size(),
                 m.residual_rms_n);
  }
  output.Write(IdentifiedParameterYaml(result));
  if (!output.Commit(&error)) return Fail(error);
  if (!cli.plot.empty()) {
    if (!WriteFitPlot(result.plots, "birotor-identify (" + result.mode + " mode): fit versus data", cli.plot, &error)) {
      return Fail("--plot " + cli.plot + ": " + error);
    }
    spdlog::info("wrote {}", cli.plot);
  }
  spdlog::info("wrote {} ({} mode, {:.2f} s)", cli.output, result.mode, elapsed_s);
  return 0;
}
