// The figures of issue 36 ("The estimator learns the vehicle it flies") for
// one flight, and the verdict against its targets: from settle_s after the
// airborne start the share of estimates that are VALID, the MAE and the
// 2-sigma share of the VALID ones, and the worst 2 s window's 2-sigma share
// of the VALID estimates from the airborne start (lift-off) on.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "samples/samples.h"

namespace birotor {

// The targets of issue 36 and the spans they are measured over.
struct MismatchTargets {
  double settle_s = 5.0;              // figures from this long after the airborne start [s]
  double min_valid_share = 0.80;      // VALID share of the estimates after settle_s [1]
  double max_valid_mae_n = 0.10;      // MAE of the VALID estimates after settle_s, worse rotor [N]
  double min_two_sigma_share = 0.90;  // 2-sigma share of the VALID estimates after settle_s [1]
  double max_two_sigma_share = 0.98;  // above: sigmas too wide to be useful [1]
  double min_window_share = 0.80;     // every window's 2-sigma share of its VALID estimates [1]
  double window_s = 2.0;              // [s]
  double window_step_s = 0.1;         // [s]
  int64_t min_window_valid = 200;     // VALID estimates a window needs to be judged
};

// The figures of one flight; NaN where nothing was VALID after settle_s.
struct MismatchTargetFigures {
  double valid_share = 0;         // VALID estimates / estimates, after settle_s [1]
  double valid_mae_n = NAN;       // mean |f_est - f_true| of the VALID ones, the worse rotor [N]
  double two_sigma_share = NAN;   // VALID ones within 2 force_std_n (the worse rotor's count) [1]
  double worst_window_share = 1;  // WorstValidWindowShare from the airborne start [1]
  int64_t estimates = 0;          // estimates with TRUTH after settle_s
};

// airborne_utime: lift-off of a flight with a ground phase; -1: the first
// estimate (an airborne start).
MismatchTargetFigures EvaluateMismatchTargets(const std::vector<ForceEstimate>& forces,
                                              const std::vector<TruthSample>& truth, int64_t airborne_utime,
                                              const MismatchTargets& targets);

// Which targets a flight missed.
struct TargetMisses {
  bool valid_share = false;
  bool mae = false;
  bool two_sigma_share = false;
  bool window = false;
  bool Any() const { return valid_share || mae || two_sigma_share || window; }
};
TargetMisses JudgeMismatchTargets(const MismatchTargetFigures& f, const MismatchTargets& targets);

// The Markdown table over seeds, one row per case: each figure as the mean
// over the seeds and, in brackets, the worst seed; the verdict "met" when
// every seed meets every target, else the targets missed with how many seeds
// missed each.
std::string MismatchTargetsTableHeader(const MismatchTargets& targets);
std::string MismatchTargetsTableRow(const std::string& name, const std::vector<MismatchTargetFigures>& seeds,
                                    const MismatchTargets& targets);

}  // namespace birotor
