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

MismatchEvalResult EvaluateMismatch(const std::vector<ForceEstimate>& forces, const std::vector<TruthSample>& truth,
                                    const MismatchEvalOptions& options);

std::string MismatchTableHeader();
std::string MismatchTableRow(const std::string& scenario, const std::string& method, const MismatchEvalResult& r);

}  // namespace birotor
