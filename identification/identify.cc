#include "identification/identify.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace birotor {
namespace {

template <class Sample>
void SortByTime(std::vector<Sample>* samples) {
  std::stable_sort(samples->begin(), samples->end(),
                   [](const Sample& a, const Sample& b) { return a.utime < b.utime; });
}

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

void SanitizeLog(SensorLog* log) {
  SortByTime(&log->strain);
  SortByTime(&log->motor);
  SortByTime(&log->imu);
  SortByTime(&log->pose);
  SortByTime(&log->loadcell);
  SortByTime(&log->truth);
  log->strain.erase(std::remove_if(log->strain.begin(), log->strain.end(),
                                   [](const StrainSample& s) {
                                     return !std::isfinite(s.deflection_rad[0]) || !std::isfinite(s.deflection_rad[1]);
                                   }),
                    log->strain.end());
}

IdentificationResult Identify(std::vector<SensorLog> logs, const VehicleParams& base,
                              const IdentificationOptions& options, IdentificationMode mode) {
  IdentificationResult result;
  result.params = base;
  for (SensorLog& log : logs) {
    SanitizeLog(&log);
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
