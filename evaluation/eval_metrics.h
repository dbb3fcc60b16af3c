// Force-estimation error against simulator truth, paired by utime (strain
// sample k and truth sample k share utime): MAE, RMSE, 95th percentile, max
// per rotor, rotor-fault detection delay and false alarms (birotor-eval).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

struct EvalOptions {
  // Estimates in the first warmup_s after the first one are not scored (the
  // filter starts with mu = 1 +- 0.3 and converges in a few tens of ms) [s].
  double warmup_s = 0.5;
  // Accuracy "outside faults" ignores this long after each input fault [s].
  double fault_exclusion_s = 0.2;
  // A change of truth thrust_scale larger than this between two samples is a step [1].
  double step_threshold = 0.05;
  // A fault flag on rotor i while truth thrust_scale_i is above this is a false alarm [1].
  double false_alarm_truth_scale = 0.9;
  // thrust_scale error is checked this long after a step [s].
  double scale_check_delay_s = 0.1;
  // Scoring starts no earlier than this (e.g. the lift-off of a flight with a
  // ground phase); -1: from the first estimate plus warmup_s [us].
  int64_t score_from_utime = -1;
};

// Error statistics of one rotor [N].
struct ErrorStats {
  int64_t count = 0;
  double mae_n = 0, rmse_n = 0, p95_n = 0, max_n = 0;
  // Share of scored estimates with |error| <= 2 force_std_n: 0.95 for an
  // honest Gaussian one sigma [1].
  double share_within_2sigma = 0;
};

struct EvalResult {
  ErrorStats rotor[kBirotorRotors];
  double mae_outside_faults_n[kBirotorRotors] = {0, 0};  // excluding fault_exclusion_s after each fault
  int64_t paired = 0;                                    // estimates with a truth sample of the same utime
  int64_t unpaired = 0;                                  // estimates without one
  int64_t nonfinite = 0;                                 // estimates with a NaN/Inf force, std or scale
  int64_t invalid = 0;                                   // scored estimates without kStatusValid
  int64_t false_alarms = 0;                              // estimates flagging rotor i while truth_i > threshold
  int64_t fault_flags = 0;                               // estimates with any rotor fault bit
  // First thrust_scale step in truth (none: step_rotor == 0).
  int step_rotor = 0;                 // 1 or 2
  double step_time_s = 0;             // [s] since the first truth sample's utime 0
  double detection_delay_s = 0;       // first fault flag of that rotor after the step; NaN if never
  double scale_error_after_step = 0;  // |estimated - true thrust_scale| scale_check_delay_s later
};

// fault_utimes: vehicle times of input faults (see ReplayStats).
EvalResult Evaluate(const std::vector<ForceEstimate>& forces, const std::vector<TruthSample>& truth,
                    const std::vector<int64_t>& fault_utimes, const EvalOptions& options);

// Markdown table: one header, one row per (scenario, method) result.
std::string MarkdownTableHeader();
std::string MarkdownTableRow(const std::string& scenario, const std::string& method, const EvalResult& result);

}  // namespace birotor
