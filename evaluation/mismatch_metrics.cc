// Model-consistency figures of one run.
#include "evaluation/mismatch_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "samples/rotor_count.h"

namespace birotor {

std::vector<ScoredEstimate> ScoreEstimates(const std::vector<ForceEstimate>& forces,
                                           const std::vector<TruthSample>& truth) {
  std::unordered_map<int64_t, size_t> truth_index;
  truth_index.reserve(truth.size());
  for (size_t i = 0; i < truth.size(); ++i) truth_index[truth[i].utime] = i;
  std::vector<ScoredEstimate> scored;
  scored.reserve(forces.size());
  for (const ForceEstimate& e : forces) {
    const auto it = truth_index.find(e.utime);
    if (it == truth_index.end()) continue;
    ScoredEstimate s;
    s.utime = e.utime;
    s.status = e.status;
    for (int i = 0; i < kBirotorRotors; ++i) {
      s.error_n[i] = e.force_n[i] - truth[it->second].force_n[i];
      s.inside[i] = std::fabs(s.error_n[i]) <= 2.0 * e.force_std_n[i];
    }
    scored.push_back(s);
  }
  return scored;
}

double WorstValidWindowShare(const std::vector<ScoredEstimate>& scored, int64_t start_utime, double window_s,
                             double window_step_s, int64_t min_valid) {
  double worst = 1.0;
  if (scored.empty()) return worst;
  // Sliding windows over the VALID estimates (a binary search for each start).
  const int64_t window_us = static_cast<int64_t>(std::llround(window_s * 1e6));
  const int64_t step_us = std::max<int64_t>(1, std::llround(window_step_s * 1e6));
  for (int64_t w = start_utime; w + window_us <= scored.back().utime; w += step_us) {
    int64_t n = 0, inside[kBirotorRotors] = {0, 0};
    for (auto it = std::lower_bound(scored.begin(), scored.end(), w,
                                    [](const ScoredEstimate&s, int64_t t) { return s.utime < t; });
         it != scored.end() && it->utime < w + window_us; ++it) {
      if (!(it->status & kStatusValid)) continue;
      ++n;
      for (int i = 0; i < kBirotorRotors; ++i) inside[i] += it->inside[i] ? 1 : 0;
    }
    if (n >= min_valid) worst = std::min(worst, static_cast<double>(std::min(inside[0], inside[1])) / n);
  }
  return worst;
}

MismatchEvalResult EvaluateMismatch(const std::vector<ForceEstimate>& forces, const std::vector<TruthSample>& truth,
                                    const MismatchEvalOptions& options) {
  MismatchEvalResult r;
  const std::vector<ScoredEstimate> scored = ScoreEstimates(forces, truth);
  if (scored.empty()) return r;
  const int64_t start = options.airborne_utime >= 0 ? options.airborne_utime : scored.front().utime;
  const int64_t settle = start + static_cast<int64_t>(options.settle_s * 1e6);
  int64_t valid = 0, counted = 0, after = 0, inside_after[kBirotorRotors] = {0, 0}, valid_before = 0;
  double sum[kBirotorRotors] = {0, 0};
  for (const ScoredEstimate& s : scored) {
    if (s.utime < start) continue;
    ++counted;
    if (s.status & kStatusValid) ++valid;
    if (s.status & kStatusThrustDeficit) ++r.thrust_deficit;
    if (s.status & (kStatusRotor1Fault | kStatusRotor2Fault)) ++r.rotor_fault;
    if (s.status & kStatusModelMismatch) {
      ++r.mismatch_estimates;
      if (r.mismatch_raised_s < 0) {
        r.mismatch_raised_s = (s.utime - start) * 1e-6;
        r.valid_before_raise = valid_before;
      }
    }
    if (r.mismatch_raised_s < 0 && (s.status & kStatusValid)) ++valid_before;
    if (s.utime >= settle) {
      ++after;
      for (int i = 0; i < kBirotorRotors; ++i) {
        sum[i] += std::fabs(s.error_n[i]);
        if (s.inside[i]) ++inside_after[i];
      }
    }
  }
  r.valid_share = counted > 0 ? static_cast<double>(valid) / counted : 0.0;
  for (int i = 0; i < kBirotorRotors; ++i) r.mae_after_settle_n[i] = after > 0 ? sum[i] / after : NAN;
  r.share_after_settle = after > 0 ? static_cast<double>(std::min(inside_after[0], inside_after[1])) / after : NAN;
  r.worst_valid_window_share =
      WorstValidWindowShare(scored, start, options.window_s, options.window_step_s, options.min_window_valid);
  return r;
}

std::string MismatchTableHeader() {
  return "| scenario | method | MAE f1 / f2 after 5 s [N] | 2-sigma share after 5 s | MODEL_MISMATCH raised [s] | "
         "VALID before it | VALID share | worst 2 s VALID share | THRUST_DEFICIT | rotor fault |\n"
         "|---|---|---|---|---|---|---|---|---|---|\n";
}

std::string MismatchTableRow(const std::string& scenario, const std::string& method, const MismatchEvalResult& r) {
  char raised[32] = "never";
  char valid_before[32] = "-";
  if (r.mismatch_raised_s >= 0) {
    std::snprintf(raised, sizeof(raised), "%.3f", r.mismatch_raised_s);
    std::snprintf(valid_before, sizeof(valid_before), "%lld", static_cast<long long>(r.valid_before_raise));
  }
  char row[512];
  std::snprintf(row, sizeof(row), "| %s | %s | %.3f / %.3f | %.3f | %s | %s | %.3f | %.3f | %lld | %lld |\n",
                scenario.c_str(), method.c_str(), r.mae_after_settle_n[0], r.mae_after_settle_n[1],
                r.share_after_settle, raised, valid_before, r.valid_share, r.worst_valid_window_share,
                static_cast<long long>(r.thrust_deficit), static_cast<long long>(r.rotor_fault));
  return row;
}

}  // namespace birotor
