#include "identification/identify.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace birotor {
namespace {

std::string Fixed(double value, int digits) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(digits);
  out << value;
  return out.str();
}

// What the mode needs of each log; one error line per missing item.
void CheckInputs(const std::vector<SensorLog>& logs, IdentificationMode mode, const IdentificationOptions& options,
                 IdentificationResult* result) {
  if (logs.empty()) result->errors.push_back("no log given");
  for (const SensorLog& log : logs) {
    const std::string name = log.source.empty() ? "log" : log.source;
    if (log.strain.empty()) result->errors.push_back(name + ": no STRAIN samples (arm deflections are needed)");
    if (log.motor.empty())
      result->errors.push_back(name + ": no MOTOR samples (rotor commands are needed)");
    else if (!HasMotorTelemetry(log)) {
      result->errors.push_back(name + ": MOTOR telemetry omega_meas is NaN throughout (ESC speed telemetry is needed)");
    }
    if (mode == IdentificationMode::kBench && log.loadcell.empty()) {
      result->errors.push_back(name +
                               ": no LOADCELL samples (bench identification needs the load cells; use --mode flight)");
    }
    const double duration_s = StrainDurationS(log);
    if (!log.strain.empty() && duration_s < options.min_duration_s) {
      result->errors.push_back(name + ": too short, " + Fixed(duration_s, 2) + " s of STRAIN data, at least " +
                               Fixed(options.min_duration_s, 1) + " s needed");
    }
  }
}

}  // namespace

IdentificationMode DetectMode(const std::vector<SensorLog>& logs) {
  if (logs.empty()) return IdentificationMode::kFlight;
  for (const SensorLog& log : logs) {
    if (log.loadcell.empty()) return IdentificationMode::kFlight;
  }
  return IdentificationMode::kBench;
}

SampleCleaningReport SanitizeLog(SensorLog* log, const IdentificationOptions& options) {
  return CleanLog(log, static_cast<int64_t>(std::llround(options.max_time_jump_s * 1e6)));
}

IdentificationResult Identify(std::vector<SensorLog> logs, const VehicleParams& base,
                              const IdentificationOptions& options, IdentificationMode mode) {
  IdentificationResult result;
  result.params = base;
  for (SensorLog& log : logs) {
    result.dropped += SanitizeLog(&log, options);
    result.sources.push_back(log.source);
  }
  if (mode == IdentificationMode::kAuto) mode = DetectMode(logs);
  result.mode = mode == IdentificationMode::kBench ? "bench" : "flight";
  CheckInputs(logs, mode, options, &result);
  if (!result.errors.empty()) return result;

  IdentifyMotorTimeConstant(logs, base, options, &result);
  if (mode == IdentificationMode::kBench) {
    IdentifyBenchThrust(logs, base, options, &result);
    IdentifyBenchArms(logs, base, options, &result);
  } else {
    IdentifyFlightArms(logs, base, options, &result);
  }
  result.ok = result.errors.empty();
  if (!result.ok) result.params = base;  // no numbers from data that could not give them
  return result;
}

}  // namespace birotor
