#include "tools/identify_multi_arm.h"

#include <spdlog/spdlog.h>

#include <cmath>

#include "identification/multi_arm_bench_fit.h"
#include "identification/multi_arm_flight_fit.h"
#include "params/identification_options_yaml.h"
#include "params/identified_description_file.h"
#include "params/vehicle_description_yaml.h"
#include "replay/multi_arm_log_loader.h"
#include "transport/output_file.h"

namespace birotor {
namespace {

void LogArm(int arm, const ArmEstimates& e) {
  for (const ParameterEstimate* p :
       {&e.stiffness, &e.damping, &e.tip_mass, &e.gauge_offset, &e.thrust_coeff, &e.motor_time_constant}) {
    spdlog::info("arm {} {:<24} {:.6g} +- {:.3g}{}", arm + 1, p->key, p->value, p->sigma,
                 p->determined ? "" : "  NOT DETERMINED");
  }
}

// The fit the request's mode names (auto: bench when every log has
// LOADCELL_N samples, flight when none has); false with *error for an
// unknown mode and for bench and flight logs together, which the N-arm fits
// do not join (the birotor's joint fit has no N-arm counterpart): a bench
// log's body is clamped, which the free-body flight model is not.
bool ChooseFlight(const std::string& mode, const std::vector<MultiArmBenchLog>& logs, bool* flight,
                  std::string* error) {
  if (mode != "auto" && mode != "bench" && mode != "flight") {
    *error = "--mode " + mode + ": bench, flight or auto";
    return false;
  }
  size_t bench_logs = 0;
  for (const MultiArmBenchLog& log : logs) bench_logs += log.loadcell.empty() ? 0 : 1;
  *flight = mode == "flight" || (mode == "auto" && bench_logs < logs.size());
  if (*flight && bench_logs > 0) {
    *error = "refused: " + std::to_string(bench_logs) +
             " bench log(s) (LOADCELL_N) in an N-arm flight fit; identify the bench first (--mode bench) and fly "
             "against the description it writes";
    return false;
  }
  return true;
}

}  // namespace

std::string IdentifyMultiArmVehicle(const MultiArmIdentifyRequest& request, const IdentificationOptions& cli_options) {
  const CalibrationFact& fact = cli_options.calibration;
  if (fact.TipMassWeighed() || fact.gauge_scale_std > 0.0) {
    return "--vehicle: --tip-mass-kg and --gauge-scale-std are not supported for N arms (the gauge scales are "
           "held at the description's)";
  }
  VehicleDescription base;
  IdentificationOptions options = cli_options;
  try {
    base = LoadVehicleDescription(request.vehicle);
    if (!request.config.empty()) options = LoadIdentificationOptions(request.config);
  } catch (const ParamError& e) {
    return e.what();
  }
  std::string error;
  std::vector<std::string> inputs = request.logs;
  inputs.push_back(request.vehicle);
  if (!CheckOutputs({request.output}, inputs, &error)) return error;
  std::vector<MultiArmBenchLog> logs;
  for (const std::string& path : request.logs) {
    MultiArmBenchLog log;
    LogLoadReport load;
    if (!LoadMultiArmBenchLog(path, request.prefix, &log, &load, &error, request.min_usable_fraction)) return error;
    if (!load.damage.empty()) spdlog::warn("{}", load.damage);
    if (log.strain.empty() && log.motor.empty() && log.loadcell.empty()) {
      return "refused: " + path + " has no STRAIN_N, MOTOR_N or LOADCELL_N samples on prefix '" + request.prefix +
             "' (a birotor log is identified without --vehicle)";
    }
    const std::string mismatch = MultiArmLogMismatch(log, base);
    if (!mismatch.empty()) return "refused: " + mismatch + " (" + request.vehicle + ")";
    spdlog::info("{}: {} STRAIN_N, {} MOTOR_N, {} LOADCELL_N, {} IMU samples{}", path, log.strain.size(),
                 log.motor.size(), log.loadcell.size(), log.imu.size(),
                 log.has_vehicle ? "" : " (no VEHICLE message: counts checked per sample)");
    logs.push_back(std::move(log));
  }
  bool flight = false;
  if (!ChooseFlight(request.mode, logs, &flight, &error)) return error;
  const char* mode = flight ? "flight" : "bench";
  spdlog::info("N-arm {} fit of {} log(s) against {}", mode, logs.size(), request.vehicle);
  const MultiArmIdentificationResult result =
      flight ? IdentifyMultiArmFlight(logs, base, options) : IdentifyMultiArmBench(logs, base, options);
  for (size_t arm = 0; arm < result.arms.size(); ++arm) LogArm(static_cast<int>(arm), result.arms[arm]);
  for (const std::string& line : result.advice) spdlog::info("advice: {}", line);
  if (!result.ok) {
    std::string reasons;
    for (const std::string& e : result.errors) reasons += (reasons.empty() ? "" : "; ") + e;
    return std::string("identification refused (N-arm ") + mode + "), no description written: " + reasons;
  }
  if (!WriteFileAtomically(request.output, IdentifiedDescriptionYaml(result, request.logs), &error)) return error;
  spdlog::info("identified description written to {}", request.output);
  return "";
}

}  // namespace birotor
