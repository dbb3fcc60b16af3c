// Figures of the model-consistency targets (issue 27, docs/mismatch.md): when
// STATUS_MODEL_MISMATCH was first raised, how much of the flight was VALID,
// the accuracy and 2-sigma share after the settling time, the worst 2-sigma
// share of the VALID estimates over any window, and THRUST_DEFICIT counts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

struct MismatchEvalOptions {
  double settle_s = 5.0;  // MAE and share are taken from this long after the first estimate [s]
  double window_s = 2.0;  // sliding window of the worst VALID 2-sigma share [s]
  double window_step_s = 0.1;
  int64_t min_window_valid = 200;  // VALID estimates a window needs to be judged
  // First estimate time used as the airborne start; -1: the first estimate [us].
  int64_t airborne_utime = -1;
};

struct MismatchEvalResult {
  double mae_after_settle_n[kBirotorRotors] = {0, 0};
  double share_after_settle = 0;   // both rotors within 2 sigma, after settle_s [1]
  double mismatch_raised_s = -1;   // first MODEL_MISMATCH after the airborne start [s]; -1 never
  int64_t mismatch_estimates = 0;  // estimates with MODEL_MISMATCH
  // VALID estimates after the airborne start and before the first
  // MODEL_MISMATCH (the price of the time to raise); -1 when never raised.
  int64_t valid_before_raise = -1;
  double valid_share = 0;               // estimates with VALID [1]
  double worst_valid_window_share = 1;  // min over windows of the VALID estimates' 2-sigma share [1]
  int64_t thrust_deficit = 0;           // estimates with THRUST_DEFICIT
  int64_t rotor_fault = 0;              // estimates with a rotor fault bit
};

// One estimate against the truth at its stamp: error f_est - f_true per
// rotor [N] and whether it lies within 2 force_std_n.
struct ScoredEstimate {
  int64_t utime = 0;
  int32_t status = 0;
  double error_n[kBirotorRotors] = {0, 0};
  bool inside[kBirotorRotors] = {true, true};
};

// The estimates that have a TRUTH sample at their stamp, in time order.
std::vector<ScoredEstimate> ScoreEstimates(const std::vector<ForceEstimate>& forces,
                                           const std::vector<TruthSample>& truth);

// The smallest 2-sigma share (both rotors: the smaller rotor's count) of the
// VALID estimates over windows [w, w + window_s), w = start_utime + k
// window_step_s, up to the last estimate; a window with fewer than
// min_valid VALID estimates is not judged. 1 when no window is judged [1].
double WorstValidWindowShare(const std::vector<ScoredEstimate>& scored, int64_t start_utime, double window_s,
                             double window_step_s, int64_t min_valid);

MismatchEvalResult EvaluateMismatch(const std::vector<ForceEstimate>& forces, const std::vector<TruthSample>& truth,
                                    const MismatchEvalOptions& options);

std::string MismatchTableHeader();
std::string MismatchTableRow(const std::string& scenario, const std::string& method, const MismatchEvalResult& r);

}  // namespace birotor
