// birotor-identify: reads lcm-logger files (bench or flight), identifies c_T,
// tau_m, k, d, the tip mass, the gauge calibration and the deflection-force
// maps with Ceres, and writes the parameter file the estimator and simulator
// load (or updates a complete one in place), plus a readable report. With
// --learned it deploys instead what the estimator learned in flight (the
// strain scales of its authenticated gauge state file, or what a re-run of a
// flight log's inputs learns) into the --update-params file.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "identification/fit_stages.h"
#include "identification/identify.h"
#include "nodes/gauge_state_file.h"
#include "nodes/learned_values_file.h"
#include "params/birotor_params_yaml.h"
#include "params/identification_options_yaml.h"
#include "params/identified_parameter_file.h"
#include "params/learned_parameter_update.h"
#include "params/vehicle_description_yaml.h"
#include "params/vehicle_section_update.h"
#include "plot/fit_plot.h"
#include "program/config_files.h"
#include "program/logging.h"
#include "program/program_options.h"
#include "replay/identification_log_loader.h"
#include "tools/identify_learned_multi_arm.h"
#include "tools/identify_learned_source.h"
#include "tools/identify_multi_arm.h"
#include "transport/host_clock.h"
#include "transport/log_io.h"
#include "transport/output_file.h"

namespace {

struct IdentifyOptions {
  std::vector<std::string> logs;
  std::string mode = "auto";
  std::string params = birotor::FindConfigFile("reference_vehicle.yaml");
  std::string config;  // optional file with an `identification:` section
  std::string output;
  std::string update_params;  // complete parameter file updated in place (FILE.bak keeps the old one)
  std::string vehicle;        // --vehicle: an N-arm description, bench fit of its counted channels
  // --learned, --site-key, --estimator-config: what the estimator learned goes into update_params (no fit)
  birotor::LearnedSourceOptions learned_source;
  birotor::LearnedDeployOptions learned_options;
  std::string report;
  std::string plot;
  double min_usable_fraction = birotor::kDefaultMinUsableLogFraction;
  bool progress = false;  // progress line on stderr even when it is not a terminal
};

// One progress line on stderr (stage, windows, elapsed, ETA), rewritten in
// place, from 2 s into the fit and at most every 0.2 s; ended by Finish().
class ProgressLine {
 public:
  void operator()(const birotor::FitProgress& at) {
    const double elapsed_s = clock_.ElapsedS();
    if (elapsed_s < 2.0 || elapsed_s - last_s_ < 0.2) return;
    last_s_ = elapsed_s;
    char eta[32] = "?";
    if (at.fraction > 0.05) std::snprintf(eta, sizeof(eta), "%.0f s", elapsed_s * (1.0 - at.fraction) / at.fraction);
    std::fprintf(stderr, "\r%-36s windows %3d  iteration %3d  elapsed %5.1f s  ETA %-8s", at.stage.c_str(), at.windows,
                 at.iteration, elapsed_s, eta);
    std::fflush(stderr);
    printed_ = true;
  }
  void Finish() {
    if (printed_) std::fprintf(stderr, "\n");
    printed_ = false;
  }

 private:
  birotor::Stopwatch clock_;
  double last_s_ = 0.0;
  bool printed_ = false;
};

// Current UTC time as 2026-12-01T02:55:00Z.
std::string UtcDateTime() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// The command line: the tool's own options, the shared ones and the
// calibration facts that go straight into the identification options.
void AddIdentifyOptions(CLI::App& app, birotor::CommonOptions* common, IdentifyOptions* cli,
                        birotor::IdentificationOptions* options) {
  using namespace birotor;
  AddCommonOptions(app, common);
  app.remove_option(app.get_option("--lcm-url"));  // offline: reads files, never LCM (issue 24)
  CLI::Option* log =
      app.add_option("--log", cli->logs, "LCM log file (repeat for several: one joint fit); required unless --learned");
  app.add_option("--mode", cli->mode, "bench (load cells), flight, or auto (bench if every log has load cells)")
      ->check(CLI::IsMember({"auto", "bench", "flight"}));
  app.add_option("--params", cli->params,
                 "Base parameter file (complete vehicle: section): masses, lengths, inertia are taken as known; "
                 "default: the --update-params file if given, else the " +
                     ConfigSearchText("reference_vehicle.yaml"));
  app.add_option("--config", cli->config,
                 "YAML file with a complete `identification:` section of options (the shipped identification.yaml "
                 "has every key at its default); none: the built-in defaults");
  app.add_option("--tip-mass-kg", options->calibration.tip_mass_kg,
                 "Weighed tip mass m_p [kg] (bench): the gauge scales are then identified; default: not weighed, "
                 "the gauge scales are the base file's gauge_scale and m_p is identified")
      ->check(CLI::PositiveNumber);
  app.add_option("--tip-mass-std-kg", options->calibration.tip_mass_std_kg,
                 "One sigma of the weighed tip mass [kg]; default 0: m_p held at --tip-mass-kg")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--gauge-scale-std", options->calibration.gauge_scale_std,
                 "One sigma of the factory gauge scale [1]; default 0: held at the base file's gauge_scale "
                 "(unless --tip-mass-kg is given). Flight: added to the sigma of k and m_p, which the "
                 "flight sees through the scale")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--vehicle", cli->vehicle,
                 "Vehicle description with N arms (e.g. config/vehicles/trirotor.yaml): bench fit of every arm and "
                 "rotor from the logs' STRAIN_N, MOTOR_N, LOADCELL_N, or (--mode flight, or auto without load "
                 "cells) flight fit of every k, c_T, tau_m from STRAIN_N, MOTOR_N, IMU; --output gets the "
                 "identified description; with --learned, the description the estimator flew (see --learned)")
      ->check(CLI::ExistingFile);
  CLI::Option* output = app.add_option("--output", cli->output, "Identified parameter file (written atomically)");
  CLI::Option* update_params =
      app.add_option("--update-params", cli->update_params,
                     "Complete parameter file (e.g. the estimator's) whose vehicle: section gets the identified values "
                     "in place, comments and other sections kept, atomically, with its mode and owner, the old file "
                     "kept as FILE.bak; a symbolic link is updated through its target (TARGET.bak); FILE.bak must be "
                     "absent or a regular file");
  CLI::Option* learned =
      app.add_option("--learned", cli->learned_source.learned,
                     "Deploy what the estimator learned in flight instead of fitting logs: its gauge state file "
                     "(estimator state_file, written at a clean stop; its mac must verify under --site-key) or an "
                     "LCM log of the flight (the estimator re-run over the log's inputs on --prefix with "
                     "--estimator-config; a recorded ESTIMATOR_STATUS is only compared, never deployed), with the "
                     "vehicle of the --update-params file (needs it; no --log, --output, --report, --plot). A strain "
                     "scale g_i multiplies gauge_scale[i], a body mass replaces body_mass_kg, a tip mass (learned from "
                     "the arm mode) replaces tip_mass_kg; an N-arm description (--vehicle, or vehicle.arms in the "
                     "file): its state file's ratio r scales every arm's tip_mass_kg (docs/identification.md)");
  CLI::Option* site_key =
      app.add_option("--site-key", cli->learned_source.site_key_file,
                     "Site key file (32 raw bytes, not group/world-writable) authenticating the --learned gauge state "
                     "file; a state file that does not verify is refused")
          ->capture_default_str();
  CLI::Option* estimator_config = app.add_option(
      "--estimator-config", cli->learned_source.estimator_config,
      "--learned LOG: estimator parameter file the log's inputs are re-run with (its estimator: section, "
      "learn_strain_scale / learn_body_mass / arm_mode_learn_tip_mass on as in the flight; the vehicle is the "
      "--update-params "
      "file's); default: the " +
          ConfigSearchText("estimator.yaml"));
  app.add_option("--learned-max-std-fraction", cli->learned_options.max_std_fraction,
                 "--learned: deploy a value only when its sigma is below this fraction of the estimator's prior "
                 "sigma (strain_scale_prior_std 0.1, body_mass_scale_prior_std 0.15 of the mass, "
                 "arm_mode_unconfirmed_tip_mass_std 0.15 of the tip mass); otherwise refuse, file untouched")
      ->check(CLI::Range(1e-3, 1.0));
  CLI::Option* report = app.add_option("--report", cli->report, "Readable report (Markdown)");
  CLI::Option* plot = app.add_option("--plot", cli->plot, "PNG of fit versus data (needs gnuplot)");
  app.add_flag("--progress", cli->progress,
               "Progress line on stderr (stage, windows, elapsed, ETA) for fits over 2 s even when stderr is not a "
               "terminal (on a terminal it is always shown)");
  learned->needs(update_params)->excludes(log)->excludes(output)->excludes(report)->excludes(plot);
  site_key->needs(learned);
  estimator_config->needs(learned);
  app.add_option("--min-usable-fraction", cli->min_usable_fraction,
                 "Refuse a log whose readable events are less than this share of its bytes")
      ->check(CLI::Range(0.0, 1.0));
}

// The base vehicle and, with --config, the fit options (the calibration facts
// of the command line kept). Returns an error message, empty on success.
std::string LoadBaseAndOptions(const IdentifyOptions& cli, birotor::BirotorParams* base,
                               birotor::IdentificationOptions* options) {
  using namespace birotor;
  try {
    // The base file's vehicle in either form; the fit is the birotor model's.
    const VehicleDescription described = LoadVehicleDescription(cli.params);
    RequireBirotor(cli.params, "birotor-identify", described);
    *base = BirotorModelOf(described);
    if (!cli.config.empty()) {
      const CalibrationFact calibration = options->calibration;  // from the command line
      *options = LoadIdentificationOptions(cli.config);
      options->calibration = calibration;
    }
  } catch (const ParamError& e) {
    return e.what();
  }
  return "";
}

// Every output of the run, opened before the fit.
struct Outputs {
  birotor::OutputFile output, report;
  birotor::ParameterFileUpdate update;
  birotor::BirotorParams update_vehicle;  // the vehicle the --update-params file describes now
};

// Outputs: never an input, each through a temporary file renamed at the
// end; opened now so an unwritable folder is refused before the fit. The
// --update-params file is the one deliberate exception: it is updated in
// place (through its link, docs/files.md), its old content kept as FILE.bak.
// Returns an error message, empty on success.
std::string OpenOutputs(const IdentifyOptions& cli, Outputs* out) {
  using namespace birotor;
  std::string error;
  std::vector<std::string> inputs = cli.logs;
  inputs.push_back(cli.params);
  inputs.push_back(cli.config);
  if ((!cli.update_params.empty() && !PrepareParameterFileUpdate(cli.update_params, &out->update, &error)) ||
      !CheckOutputs({cli.output, cli.report, cli.plot, out->update.backup}, inputs, &error) ||
      (!cli.update_params.empty() && !CheckOutputs({cli.update_params, cli.output, cli.report, cli.plot},
                                                   {cli.logs.begin(), cli.logs.end()}, &error)) ||
      (!cli.output.empty() && !out->output.Open(cli.output, &error)) ||
      (!cli.report.empty() && !out->report.Open(cli.report, &error))) {
    return error.rfind("--update-params", 0) == 0 || cli.update_params.empty()
               ? error
               : "--update-params " + cli.update_params + ": " + error;
  }
  return "";
}

// The vehicle: section of text (named file) read into vehicle; throws ParamError.
void ReadVehicleSection(const std::string& text, const std::string& file, birotor::BirotorParams* vehicle) {
  using namespace birotor;
  WithFileErrors(file, [&] {
    YamlSection root = YamlSection::LoadString(text, file);
    ReadBirotorParams(root.Section("vehicle"), vehicle);
  });
}

// The file to update must be complete before the fit, so a fit is never lost
// to it. Returns an error message, empty on success.
std::string CheckUpdateTarget(const IdentifyOptions& cli, const birotor::BirotorParams& base, Outputs* out) {
  using namespace birotor;
  if (cli.update_params.empty()) return "";
  try {  // from the text already read (a regular file, docs/files.md), not a second read
    ReadVehicleSection(out->update.text, cli.update_params, &out->update_vehicle);
  } catch (const ParamError& e) {
    return e.what();
  }
  std::string unused, error;
  if (!UpdateVehicleSection(out->update.text, base, "", &unused, &error)) {
    return "--update-params " + cli.update_params + ": " + error;
  }
  return "";
}

// Every log read into a SensorLog, its damage and decode errors logged.
bool LoadLogs(const IdentifyOptions& cli, const std::string& prefix, std::vector<birotor::SensorLog>* logs,
              std::string* error) {
  using namespace birotor;
  for (const std::string& path : cli.logs) {
    SensorLog log;
    LogLoadReport load;
    if (!LoadSensorLog(path, prefix, &log, &load, error, cli.min_usable_fraction)) return false;
    if (!load.damage.empty()) spdlog::warn("{}", load.damage);
    if (load.decode_errors > 0) spdlog::warn("{}: {} events did not decode and were skipped", path, load.decode_errors);
    spdlog::info("{}: {} strain, {} motor, {} imu, {} loadcell samples", path, log.strain.size(), log.motor.size(),
                 log.imu.size(), log.loadcell.size());
    logs->push_back(std::move(log));
  }
  return true;
}

// The fit, with the progress line on a terminal or with --progress.
birotor::IdentificationResult RunIdentification(const IdentifyOptions& cli, std::vector<birotor::SensorLog> logs,
                                                const birotor::BirotorParams& base,
                                                birotor::IdentificationOptions options) {
  using namespace birotor;
  const IdentificationMode mode = cli.mode == "bench"    ? IdentificationMode::kBench
                                  : cli.mode == "flight" ? IdentificationMode::kFlight
                                                         : IdentificationMode::kAuto;
  ProgressLine progress;
  if (cli.progress || isatty(STDERR_FILENO)) options.progress = [&progress](const FitProgress& at) { progress(at); };
  IdentificationResult result = Identify(std::move(logs), base, options, mode);
  progress.Finish();
  return result;
}

// The identified values, the undetermined ones, the maps, shares and correlations.
void LogEstimates(const birotor::IdentificationResult& result) {
  using namespace birotor;
  for (const IdentificationWarning& w : result.warnings) spdlog::warn("{}", WarningText(w));
  for (const ParameterEstimate& e : result.estimates) {
    if (e.determined && ReportStatus(e) != "determined") {  // the report's words: a sigma above the value, no step
      spdlog::warn("{:6s} = {:.6g} +- {:.3g}: {} (the report says why)", e.symbol, e.value, e.sigma, ReportStatus(e));
    } else if (e.determined) {
      spdlog::info("{:6s} = {:.6g} +- {:.3g} ({:.3f} %)", e.symbol, e.value, e.sigma, 100.0 * e.sigma / e.value);
    } else {
      spdlog::warn("{:6s} NOT DETERMINED by these logs: {} keeps the base file's value, marked so in the output",
                   e.symbol, e.key);
    }
  }
  for (const DeflectionForceMap& m : result.maps) {
    spdlog::info("arm {} map: {} coefficients, residual RMS {:.4f} N", m.arm + 1, m.coefficients.size(),
                 m.residual_rms_n);
  }
  for (const LogShares& shares : result.log_shares) spdlog::info("information share {}", LogSharesText(shares));
  for (const DeterminedCombination& c : result.correlations) spdlog::warn("{}", CombinationText(c));
}

// Stamp: the date and what the values came from; the estimator logs it at start-up.
std::string ProvenanceStamp(const birotor::IdentificationResult& result) {
  std::string stamp = UtcDateTime() + " by birotor-identify (" + result.mode + " mode) from";
  for (const std::string& source : result.sources) stamp += " " + std::filesystem::path(source).filename().string();
  if (result.has_calibration_fact) stamp += "; " + birotor::CalibrationFactText(result);
  return stamp;
}

// --update-params: only what these logs determined is deployed, every other
// value stays the file's own, whatever the base (--params) said; the new text
// must load back as the identified vehicle before it replaces the old file.
// Returns an error message, empty on success.
std::string WriteVehicleInPlace(const IdentifyOptions& cli, const birotor::BirotorParams& deployed,
                                const std::string& stamp, const Outputs& out);

std::string UpdateParamsInPlace(const IdentifyOptions& cli, const birotor::IdentificationOptions& options,
                                const birotor::IdentificationResult& result, const std::string& stamp,
                                const Outputs& out) {
  using namespace birotor;
  BirotorParams deployed = out.update_vehicle;
  for (const ParameterEstimate& e : result.estimates) {
    if (e.determined) SetVehicleValue(e.key, e.value, &deployed);
  }
  if (options.calibration.TipMassWeighed()) deployed.tip_mass_kg = result.params.tip_mass_kg;  // the weighed fact
  return WriteVehicleInPlace(cli, deployed, stamp, out);
}

// The --update-params file's vehicle section set to `deployed` (every other
// byte kept), read back and checked, then committed with FILE.bak. Returns
// an error message, empty on success.
std::string WriteVehicleInPlace(const IdentifyOptions& cli, const birotor::BirotorParams& deployed,
                                const std::string& stamp, const Outputs& out) {
  using namespace birotor;
  std::string updated, error;
  if (!UpdateVehicleSection(out.update.text, deployed, stamp, &updated, &error)) {
    return "--update-params " + cli.update_params + ": " + error;
  }
  try {
    BirotorParams check;
    ReadVehicleSection(updated, cli.update_params, &check);
    if (BirotorParamsYaml(check) != BirotorParamsYaml(deployed)) {
      return "--update-params " + cli.update_params +
             ": the updated text does not read back as the deployed values; file left unchanged";
    }
  } catch (const ParamError& e) {
    return std::string(e.what()) + "; file left unchanged";
  }
  if (!CommitParameterFileUpdate(out.update, updated, &error)) return "--update-params: " + error;
  spdlog::info("updated the vehicle section of {} in place (previous file: {})", out.update.target, out.update.backup);
  return "";
}

// The parameter file(s) and the plot. A failed plot is an error (exit 1),
// but the parameter file stands. Returns an error message, empty on success.
std::string WriteResults(const IdentifyOptions& cli, const birotor::IdentificationOptions& options,
                         const birotor::IdentificationResult& result, Outputs* out) {
  using namespace birotor;
  const std::string stamp = ProvenanceStamp(result);
  std::string error;
  if (out->output.is_open()) {
    std::string text;
    if (!UpdateVehicleSection(IdentifiedParameterYaml(result), result.params, stamp, &text, &error)) return error;
    out->output.Write(text);
    if (!out->output.Commit(&error)) return error;
    spdlog::info("wrote {}", cli.output);
  }
  if (!cli.update_params.empty()) {
    error = UpdateParamsInPlace(cli, options, result, stamp, *out);
    if (!error.empty()) return error;
  }
  if (!cli.plot.empty()) {
    if (!WriteFitPlot(result.plots, "birotor-identify (" + result.mode + " mode): fit versus data", cli.plot, &error)) {
      return "--plot " + cli.plot + ": " + error;
    }
    spdlog::info("wrote {}", cli.plot);
  }
  return "";
}

// --learned: what the estimator learned (its authenticated gauge state file,
// or a re-run of a flight log's inputs, tools/identify_learned_source.h) into
// the --update-params file. A state file names the vehicle it was learned on
// (a checksum of the vehicle section), as does a log's recorded status: a
// file for another vehicle, or one already updated with it (its gauge_scale
// changed), is refused, so a value is never applied twice. N arms:
// tools/identify_learned_multi_arm.h. Returns an error message, "" on success.
std::string DeployLearned(const IdentifyOptions& cli, const std::string& prefix) {
  using namespace birotor;
  Outputs out;
  std::string error;
  if (!PrepareParameterFileUpdate(cli.update_params, &out.update, &error) ||
      !CheckOutputs({cli.update_params, out.update.backup},
                    {cli.learned_source.learned, cli.learned_source.estimator_config, cli.learned_source.site_key_file},
                    &error)) {
    return "--update-params " + cli.update_params + ": " + error;
  }
  LearnedSourceOptions source = cli.learned_source;
  if (!cli.vehicle.empty() || IsArmsForm(out.update.text)) {  // routed as --vehicle routes a fit
    return DeployLearnedMultiArm({cli.vehicle, cli.update_params, source, cli.learned_options, UtcDateTime()},
                                 out.update);
  }
  try {
    ReadVehicleSection(out.update.text, cli.update_params, &out.update_vehicle);
  } catch (const ParamError& e) {
    return e.what();
  }
  source.prefix = prefix;
  source.min_usable_fraction = cli.min_usable_fraction;
  LearnedVehicleValues learned;
  if (!(error = ReadTrustedLearnedValues(source, out.update_vehicle, cli.update_params, &learned)).empty()) {
    return error;
  }
  BirotorParams deployed = out.update_vehicle;
  std::vector<LearnedChange> changes;
  if (!ApplyLearnedValues(learned, cli.learned_options, source.learned, cli.update_params, &deployed, &changes,
                          &error)) {
    return error;
  }
  const std::string stamp = UtcDateTime() + " by birotor-identify from what the estimator learned (" +
                            std::filesystem::path(source.learned).filename().string() +
                            "): " + LearnedChangesText(changes);
  spdlog::info("learned: {}", LearnedChangesText(changes));
  return WriteVehicleInPlace(cli, deployed, stamp, out);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace birotor;
  CommonOptions common;
  IdentifyOptions cli;
  IdentificationOptions options;
  CLI::App app(
      "Identify the birotor's c_T, tau_m, k, d, tip mass, gauge calibration and deflection-force maps from "
      "LCM logs",
      "birotor-identify");
  AddIdentifyOptions(app, &common, &cli, &options);
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-identify", common.log_level);
  if (!cli.learned_source.learned.empty()) {
    const std::string error = DeployLearned(cli, common.prefix);
    return error.empty() ? 0 : ReportError(error);
  }
  if (cli.logs.empty()) return ReportError("--log is required (or --learned STATE) (see --help)", kExitUsage);
  if (cli.output.empty() && cli.update_params.empty()) {
    return ReportError("nothing to write: give --output FILE or --update-params FILE (or both)");
  }
  if (!cli.vehicle.empty()) {
    if (cli.output.empty() || !cli.update_params.empty())
      return ReportError("--vehicle writes --output FILE (not --update-params)");
    const std::string error = IdentifyMultiArmVehicle(
        {cli.logs, cli.mode, cli.vehicle, common.prefix, cli.output, cli.config, cli.min_usable_fraction}, options);
    return error.empty() ? 0 : ReportError(error);
  }
  if (!cli.update_params.empty() && app.get_option("--params")->count() == 0) cli.params = cli.update_params;

  BirotorParams base;
  std::string error = LoadBaseAndOptions(cli, &base, &options);
  if (!error.empty()) return ReportError(error);
  spdlog::info("base parameters {} (checksum {})", cli.params, FileChecksum(cli.params));
  Outputs out;
  if (!(error = OpenOutputs(cli, &out)).empty() || !(error = CheckUpdateTarget(cli, base, &out)).empty()) {
    return ReportError(error);
  }

  const Stopwatch stopwatch;
  std::vector<SensorLog> logs;
  if (!LoadLogs(cli, common.prefix, &logs, &error)) return ReportError(error);
  const IdentificationResult result = RunIdentification(cli, std::move(logs), base, options);
  const double elapsed_s = stopwatch.ElapsedS();
  if (result.dropped.total() > 0) {
    spdlog::warn("bad samples (non-finite, bad stamp, out of order, duplicate): {}",
                 DroppedSamplesText(result.dropped));
  }
  if (out.report.is_open()) {
    out.report.Write(IdentificationReport(result));
    if (!out.report.Commit(&error)) return ReportError(error);
  }
  if (!result.ok) {
    std::string reasons;
    for (const std::string& e : result.errors) reasons += (reasons.empty() ? "" : "; ") + e;
    return ReportError("identification refused (" + result.mode + " mode), no parameter file written: " + reasons);
  }
  LogEstimates(result);
  if (!(error = WriteResults(cli, options, result, &out)).empty()) return ReportError(error);
  spdlog::info("identified in {} mode in {:.2f} s; calibration fact: {}", result.mode, elapsed_s,
               result.has_calibration_fact ? CalibrationFactText(result) : "none needed");
  return 0;
}
