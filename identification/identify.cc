#include "identification/identify.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "samples/rotor_count.h"

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
// In a joint bench + flight run (mode kAuto) each log is fitted in its own
// mode, a flight log on flight_base (the bench logs' fit: its gauge
// calibration is the one the flight reads its deflections through).
void CompareLogs(const std::vector<SensorLog>& logs, const BirotorParams& base, const BirotorParams& flight_base,
                 const IdentificationOptions& options, IdentificationMode mode, IdentificationResult* result) {
  std::vector<IdentificationResult> singles;
  for (const SensorLog& log : logs) {
    const IdentificationMode own = mode == IdentificationMode::kAuto ? DetectMode({log}) : mode;
    singles.push_back(Identify({log}, own == IdentificationMode::kFlight ? flight_base : base, options, own));
  }
  for (const ParameterEstimate& joint : result->estimates) {
    LogShares shares{joint.symbol, {}, {}};
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
      shares.logs.push_back(logs[l].source);
      shares.shares.push_back(share);
    }
    result->log_shares.push_back(shares);
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

void IdentifyBenchAndFlight(const std::vector<SensorLog>& bench_logs, const std::vector<SensorLog>& flight_logs,
                            const BirotorParams& base, const IdentificationOptions& options,
                            IdentificationResult* result) {
  result->mode = "bench+flight";
  result->bench_params = base;
  CheckInputs(bench_logs, IdentificationMode::kBench, options, result);
  CheckInputs(flight_logs, IdentificationMode::kFlight, options, result);
  if (!result->errors.empty()) return;
  std::vector<SensorLog> all = bench_logs;
  all.insert(all.end(), flight_logs.begin(), flight_logs.end());
  IdentifyMotorTimeConstant(all, base, options, result);
  // The bench logs alone first: the start of the joint fit, the static maps,
  // the gauge calibration (bench only) and the calibration fact.
  IdentificationResult bench;
  bench.params = result->params;
  IdentifyBenchThrust(bench_logs, bench.params, options, &bench);
  IdentifyBenchArms(bench_logs, bench.params, options, &bench);
  result->errors.insert(result->errors.end(), bench.errors.begin(), bench.errors.end());
  result->warnings.insert(result->warnings.end(), bench.warnings.begin(), bench.warnings.end());
  result->maps = bench.maps;
  result->plots = bench.plots;
  result->has_calibration_fact = bench.has_calibration_fact;
  result->calibration_fact = bench.calibration_fact;
  for (int arm = 0; arm < kBirotorRotors; ++arm) result->factory_gauge_scale[arm] = bench.factory_gauge_scale[arm];
  result->correlations = bench.correlations;
  result->bench_params = bench.params;
  if (!result->errors.empty()) return;
  // Each log alone before the joint fit: its share of every parameter, and
  // logs of two vehicles are refused without a joint fit of both.
  IdentificationResult each;
  each.estimates = result->estimates;
  each.estimates.insert(each.estimates.end(), bench.estimates.begin(), bench.estimates.end());
  CompareLogs(all, base, bench.params, options, IdentificationMode::kAuto, &each);
  result->log_shares = each.log_shares;
  if (!each.errors.empty()) {
    result->errors = each.errors;
    return;
  }
  result->params = bench.params;
  IdentifyFlightArms(flight_logs, bench.params, options, result, &bench_logs);
  // The gauge calibration has no flight information: the bench's, held in the joint fit.
  for (ParameterEstimate e : bench.estimates) {
    if (e.symbol.rfind("s_", 0) != 0 && e.symbol.rfind("o_", 0) != 0) continue;
    e.note.remarks.push_back(EstimateRemark::kBenchLogsAlone);
    result->estimates.push_back(e);
  }
}

IdentificationResult Identify(std::vector<SensorLog> logs, const BirotorParams& base,
                              const IdentificationOptions& options, IdentificationMode mode) {
  IdentificationResult result;
  result.params = base;
  for (SensorLog& log : logs) {
    result.dropped += SanitizeLog(&log, options);
    result.sources.push_back(log.source);
  }
  if (mode == IdentificationMode::kAuto) {
    std::vector<SensorLog> bench_logs, flight_logs;
    for (SensorLog& log : logs) (log.loadcell.empty() ? flight_logs : bench_logs).push_back(log);
    if (!bench_logs.empty() && !flight_logs.empty()) {
      IdentifyBenchAndFlight(bench_logs, flight_logs, base, options, &result);
      result.ok = result.errors.empty();
      if (!result.ok) result.params = base;
      return result;
    }
    mode = DetectMode(logs);
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
  if (logs.size() > 1) CompareLogs(logs, base, base, options, mode, &result);
  result.ok = result.errors.empty();
  if (!result.ok) result.params = base;  // no numbers from data that could not give them
  return result;
}

}  // namespace birotor
