#include "identification/identify.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
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

// Several logs: each one alone as well, to say which log determines which
// parameter (its share of the information 1 / sigma^2) and to refuse logs
// that disagree by more than consistency_sigmas combined sigmas (two
// vehicles, a changed vehicle, a broken sensor).
void CompareLogs(const std::vector<SensorLog>& logs, const VehicleParams& base, const IdentificationOptions& options,
                 IdentificationMode mode, IdentificationResult* result) {
  std::vector<IdentificationResult> singles;
  for (const SensorLog& log : logs) singles.push_back(Identify({log}, base, options, mode));
  for (const ParameterEstimate& joint : result->estimates) {
    std::string shares;
    double information = 0.0;
    std::vector<std::pair<size_t, const ParameterEstimate*>> alone;
    for (size_t l = 0; l < singles.size(); ++l) {
      for (const ParameterEstimate& e : singles[l].estimates) {
        if (e.symbol == joint.symbol && singles[l].ok && e.determined && e.sigma > 0.0) {
          alone.emplace_back(l, &e);
          information += 1.0 / (e.sigma * e.sigma);
        }
      }
    }
    for (size_t l = 0; l < singles.size(); ++l) {
      double share = 0.0;
      for (const auto& [index, e] : alone) {
        if (index == l) share = 1.0 / (e->sigma * e->sigma) / information;
      }
      shares += (l == 0 ? "" : ", ") + logs[l].source + " " + Fixed(100.0 * share, 1) + " %";
    }
    result->log_shares.push_back(joint.symbol + ": " + shares);
    for (size_t a = 0; a < alone.size(); ++a) {
      for (size_t b = a + 1; b < alone.size(); ++b) {
        const ParameterEstimate& ea = *alone[a].second;
        const ParameterEstimate& eb = *alone[b].second;
        const double z = std::abs(ea.value - eb.value) / std::hypot(ea.sigma, eb.sigma);
        if (z <= options.consistency_sigmas) continue;
        std::ostringstream line;
        line.precision(6);
        line << "logs disagree on " << joint.symbol << ": " << logs[alone[a].first].source << " " << ea.value << " +- "
             << std::setprecision(3) << ea.sigma << ", " << logs[alone[b].first].source << " " << std::setprecision(6)
             << eb.value << " +- " << std::setprecision(3) << eb.sigma << " (" << std::setprecision(3) << z
             << " combined sigmas): not the same vehicle?";
        result->errors.insert(result->errors.begin(), line.str());
      }
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
  if (mode == IdentificationMode::kAuto) {
    mode = DetectMode(logs);
    if (mode == IdentificationMode::kFlight) {
      for (const SensorLog& log : logs) {
        if (!log.loadcell.empty()) {
          result.errors.push_back(
              "bench and flight logs mixed (" + log.source +
              " has LOADCELL samples, another log has none): identify them separately or pass --mode");
          result.mode = "mixed";
          return result;
        }
      }
    }
  }
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
  // Also when the joint fit failed: two vehicles make a joint fit misfit, and
  // the disagreement is the reason to report first.
  if (logs.size() > 1) CompareLogs(logs, base, options, mode, &result);
  result.ok = result.errors.empty();
  if (!result.ok) result.params = base;  // no numbers from data that could not give them
  return result;
}

}  // namespace birotor
