// Force error statistics against truth.
#include "evaluation/eval_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <unordered_map>

#include "numerics/percentile.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

ErrorStats Summarize(std::vector<double>* errors, int64_t within_2sigma = 0) {
  ErrorStats stats;
  stats.count = static_cast<int64_t>(errors->size());
  if (errors->empty()) {
    stats.mae_n = stats.rmse_n = stats.p95_n = stats.max_n = stats.share_within_2sigma = kNaN;
    return stats;
  }
  stats.share_within_2sigma = static_cast<double>(within_2sigma) / static_cast<double>(errors->size());
  double sum = 0, sum_sq = 0;
  for (double e : *errors) {
    sum += e;
    sum_sq += e * e;
  }
  const double n = static_cast<double>(errors->size());
  stats.mae_n = sum / n;
  stats.rmse_n = std::sqrt(sum_sq / n);
  stats.max_n = *std::max_element(errors->begin(), errors->end());
  stats.p95_n = Percentile(errors->begin(), errors->end(), 0.95);
  return stats;
}

bool Finite(const ForceEstimate& e) {
  for (int i = 0; i < kBirotorRotors; ++i) {
    if (!std::isfinite(e.force_n[i]) || !std::isfinite(e.force_std_n[i]) || !std::isfinite(e.thrust_scale[i])) {
      return false;
    }
  }
  return true;
}

int32_t FaultBit(int rotor) { return rotor == 1 ? kStatusRotor1Fault : kStatusRotor2Fault; }

}  // namespace

EvalResult Evaluate(const std::vector<ForceEstimate>& forces, const std::vector<TruthSample>& truth,
                    const std::vector<int64_t>& fault_utimes, const EvalOptions& options) {
  EvalResult result;
  std::unordered_map<int64_t, size_t> truth_index;
  truth_index.reserve(truth.size());
  for (size_t i = 0; i < truth.size(); ++i) truth_index[truth[i].utime] = i;

  // First thrust_scale step in truth.
  int64_t step_utime = -1;
  for (size_t i = 1; i < truth.size() && result.step_rotor == 0; ++i) {
    for (int r = 0; r < kBirotorRotors; ++r) {
      if (std::abs(truth[i].thrust_scale[r] - truth[i - 1].thrust_scale[r]) > options.step_threshold) {
        result.step_rotor = r + 1;
        step_utime = truth[i].utime;
        break;
      }
    }
  }
  result.step_time_s = step_utime >= 0 ? static_cast<double>(step_utime) * 1e-6 : kNaN;
  result.detection_delay_s = kNaN;
  result.scale_error_after_step = kNaN;
  const int64_t check_utime = step_utime + static_cast<int64_t>(std::llround(options.scale_check_delay_s * 1e6));

  const int64_t warmup_us = static_cast<int64_t>(std::llround(options.warmup_s * 1e6));
  const int64_t exclusion_us = static_cast<int64_t>(std::llround(options.fault_exclusion_s * 1e6));
  std::vector<double> errors[kBirotorRotors], errors_outside[kBirotorRotors];
  int64_t within_2sigma[kBirotorRotors] = {0, 0};
  int64_t first_utime = forces.empty() ? 0 : forces.front().utime;
  size_t next_fault = 0;
  int64_t last_fault_utime = std::numeric_limits<int64_t>::min() / 2;
  for (const ForceEstimate& e : forces) {
    if (!Finite(e)) ++result.nonfinite;
    if (e.status & (kStatusRotor1Fault | kStatusRotor2Fault)) ++result.fault_flags;
    auto it = truth_index.find(e.utime);
    if (it == truth_index.end()) {
      ++result.unpaired;
      continue;
    }
    ++result.paired;
    const TruthSample& t = truth[it->second];
    for (int r = 0; r < kBirotorRotors; ++r) {
      if ((e.status & FaultBit(r + 1)) && t.thrust_scale[r] > options.false_alarm_truth_scale) {
        ++result.false_alarms;
      }
    }
    if (step_utime >= 0 && e.utime >= step_utime) {
      if (std::isnan(result.detection_delay_s) && (e.status & FaultBit(result.step_rotor))) {
        result.detection_delay_s = static_cast<double>(e.utime - step_utime) * 1e-6;
      }
      if (std::isnan(result.scale_error_after_step) && e.utime >= check_utime) {
        const int r = result.step_rotor - 1;
        result.scale_error_after_step = std::abs(e.thrust_scale[r] - t.thrust_scale[r]);
      }
    }
    if (e.utime - first_utime < warmup_us || e.utime < options.score_from_utime) continue;
    if (!(e.status & kStatusValid)) ++result.invalid;
    while (next_fault < fault_utimes.size() && fault_utimes[next_fault] <= e.utime) {
      last_fault_utime = fault_utimes[next_fault++];
    }
    const bool near_fault = e.utime - last_fault_utime < exclusion_us;
    for (int r = 0; r < kBirotorRotors; ++r) {
      // A non-finite estimate scores as an infinite error, never silently.
      const double error =
          std::isfinite(e.force_n[r]) ? std::abs(e.force_n[r] - t.force_n[r]) : std::numeric_limits<double>::infinity();
      errors[r].push_back(error);
      if (error <= 2.0 * e.force_std_n[r]) ++within_2sigma[r];
      if (!near_fault) errors_outside[r].push_back(error);
    }
  }
  for (int r = 0; r < kBirotorRotors; ++r) {
    result.rotor[r] = Summarize(&errors[r], within_2sigma[r]);
    result.mae_outside_faults_n[r] = Summarize(&errors_outside[r]).mae_n;
  }
  return result;
}

std::string MarkdownTableHeader() {
  return "| scenario | method | MAE f1 [N] | MAE f2 [N] | RMSE f1 [N] | RMSE f2 [N] | "
         "p95 f1 [N] | p95 f2 [N] | max f1 [N] | max f2 [N] | MAE excl. faults [N] | "
         "fault delay [ms] | scale err +100 ms | false alarms | non-finite | scored | "
         "within 2 sigma f1 / f2 |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
}

std::string MarkdownTableRow(const std::string& scenario, const std::string& method, const EvalResult& r) {
  char delay[32] = "-", scale[32] = "-";
  if (r.step_rotor != 0) {
    if (std::isnan(r.detection_delay_s)) {
      std::snprintf(delay, sizeof(delay), "not detected");
    } else {
      std::snprintf(delay, sizeof(delay), "%.0f", r.detection_delay_s * 1e3);
    }
    std::snprintf(scale, sizeof(scale), "%.4f", r.scale_error_after_step);
  }
  char row[1024];
  std::snprintf(row, sizeof(row),
                "| %s | %s | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | "
                "%.4f / %.4f | %s | %s | %lld | %lld | %lld | %.3f / %.3f |\n",
                scenario.c_str(), method.c_str(), r.rotor[0].mae_n, r.rotor[1].mae_n, r.rotor[0].rmse_n,
                r.rotor[1].rmse_n, r.rotor[0].p95_n, r.rotor[1].p95_n, r.rotor[0].max_n, r.rotor[1].max_n,
                r.mae_outside_faults_n[0], r.mae_outside_faults_n[1], delay, scale,
                static_cast<long long>(r.false_alarms), static_cast<long long>(r.nonfinite),
                static_cast<long long>(r.rotor[0].count), r.rotor[0].share_within_2sigma,
                r.rotor[1].share_within_2sigma);
  return row;
}

}  // namespace birotor
