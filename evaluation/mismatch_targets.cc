// Issue 36's figures of one flight and their table over seeds.
#include "evaluation/mismatch_targets.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "evaluation/mismatch_metrics.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {

// Over the seeds: the mean of the figure over the seeds that have it, and
// the worst seed (largest badness(value)); a seed without the figure (NaN:
// nothing VALID) is the worst.
struct Spread {
  double mean = NAN;
  double worst = NAN;
  bool worst_missing = false;
};

template <typename Get, typename Badness>
Spread SpreadOf(const std::vector<MismatchTargetFigures>& seeds, Get get, Badness badness) {
  Spread s;
  double sum = 0;
  int have = 0;
  for (const MismatchTargetFigures& f : seeds) {
    const double v = get(f);
    if (std::isnan(v)) {
      s.worst_missing = true;
      continue;
    }
    sum += v;
    ++have;
    if (std::isnan(s.worst) || badness(v) > badness(s.worst)) s.worst = v;
  }
  if (have > 0) s.mean = sum / have;
  return s;
}

// "mean (worst)"; "-" without a value, "none VALID" for a seed without one.
std::string Cell(const Spread& s) {
  if (std::isnan(s.mean)) return "none VALID";
  char text[64];
  if (s.worst_missing) {
    std::snprintf(text, sizeof(text), "%.3f (none VALID)", s.mean);
  } else {
    std::snprintf(text, sizeof(text), "%.3f (%.3f)", s.mean, s.worst);
  }
  return text;
}

}  // namespace

MismatchTargetFigures EvaluateMismatchTargets(const std::vector<ForceEstimate>& forces,
                                              const std::vector<TruthSample>& truth, int64_t airborne_utime,
                                              const MismatchTargets& targets) {
  MismatchTargetFigures f;
  const std::vector<ScoredEstimate> scored = ScoreEstimates(forces, truth);
  if (scored.empty()) return f;
  const int64_t start = airborne_utime >= 0 ? airborne_utime : scored.front().utime;
  const int64_t settle = start + std::llround(targets.settle_s * 1e6);
  int64_t valid = 0, inside[kBirotorRotors] = {0, 0};
  double sum_n[kBirotorRotors] = {0, 0};
  for (const ScoredEstimate& s : scored) {
    if (s.utime < settle) continue;
    ++f.estimates;
    if (!(s.status & kStatusValid)) continue;
    ++valid;
    for (int i = 0; i < kBirotorRotors; ++i) {
      sum_n[i] += std::fabs(s.error_n[i]);
      inside[i] += s.inside[i] ? 1 : 0;
    }
  }
  f.valid_share = f.estimates > 0 ? static_cast<double>(valid) / static_cast<double>(f.estimates) : 0.0;
  if (valid > 0) {
    f.valid_mae_n = std::max(sum_n[0], sum_n[1]) / static_cast<double>(valid);
    f.two_sigma_share = static_cast<double>(std::min(inside[0], inside[1])) / static_cast<double>(valid);
  }
  f.worst_window_share =
      WorstValidWindowShare(scored, start, targets.window_s, targets.window_step_s, targets.min_window_valid);
  return f;
}

TargetMisses JudgeMismatchTargets(const MismatchTargetFigures& f, const MismatchTargets& targets) {
  TargetMisses m;
  m.valid_share = !(f.valid_share >= targets.min_valid_share);
  m.mae = !(f.valid_mae_n <= targets.max_valid_mae_n);  // NaN (nothing VALID) misses
  m.two_sigma_share =
      !(f.two_sigma_share >= targets.min_two_sigma_share && f.two_sigma_share <= targets.max_two_sigma_share);
  m.window = !(f.worst_window_share >= targets.min_window_share);
  return m;
}

std::string MismatchTargetsTableHeader(const MismatchTargets& t) {
  char text[768];
  std::snprintf(text, sizeof(text),
                "| case | seeds | VALID share from %g s (>= %.2f) | MAE of VALID [N] (<= %.2f) | "
                "2-sigma share of VALID (%.2f-%.2f) | worst %g s window of VALID from lift-off (>= %.2f) | "
                "verdict |\n|---|---|---|---|---|---|---|\n",
                t.settle_s, t.min_valid_share, t.max_valid_mae_n, t.min_two_sigma_share, t.max_two_sigma_share,
                t.window_s, t.min_window_share);
  return text;
}

std::string MismatchTargetsTableRow(const std::string& name, const std::vector<MismatchTargetFigures>& seeds,
                                    const MismatchTargets& targets) {
  if (seeds.empty()) return "| " + name + " | 0 | - | - | - | - | - |\n";
  const double band_mid = 0.5 * (targets.min_two_sigma_share + targets.max_two_sigma_share);
  const Spread valid = SpreadOf(
      seeds, [](const auto& f) { return f.valid_share; }, [](double v) { return -v; });
  const Spread mae = SpreadOf(
      seeds, [](const auto& f) { return f.valid_mae_n; }, [](double v) { return v; });
  // The worse of a share below the band and one above it: the farther from the band's middle.
  const Spread share = SpreadOf(
      seeds, [](const auto& f) { return f.two_sigma_share; }, [band_mid](double v) { return std::fabs(v - band_mid); });
  const Spread window = SpreadOf(
      seeds, [](const auto& f) { return f.worst_window_share; }, [](double v) { return -v; });
  int missed[4] = {0, 0, 0, 0};
  for (const MismatchTargetFigures& f : seeds) {
    const TargetMisses m = JudgeMismatchTargets(f, targets);
    missed[0] += m.valid_share;
    missed[1] += m.mae;
    missed[2] += m.two_sigma_share;
    missed[3] += m.window;
  }
  std::string verdict;
  const char* names[4] = {"VALID", "MAE", "2-sigma", "window"};
  for (int k = 0; k < 4; ++k) {
    if (missed[k] == 0) continue;
    verdict += (verdict.empty() ? "NOT met: " : ", ") + std::string(names[k]) + " " + std::to_string(missed[k]) + "/" +
               std::to_string(seeds.size());
  }
  if (verdict.empty()) verdict = "met";
  return "| " + name + " | " + std::to_string(seeds.size()) + " | " + Cell(valid) + " | " + Cell(mae) + " | " +
         Cell(share) + " | " + Cell(window) + " | " + verdict + " |\n";
}

}  // namespace birotor
