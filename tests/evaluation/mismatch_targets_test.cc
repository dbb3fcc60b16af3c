// Issue 36's figures (evaluation/mismatch_targets.h) on hand-made 1 kHz
// series with exact expected numbers: the VALID share, MAE and 2-sigma
// share from 5 s after the airborne start, the worst 2 s window of VALID
// estimates from lift-off, the verdict and the table row over seeds.
#include "evaluation/mismatch_targets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tests/evaluation/synthetic_force_series.h"

namespace birotor {
namespace {

using Series = SyntheticForceSeries;
template <typename StatusOf, typename ErrorOf>
Series Make(int64_t count, StatusOf status_of, ErrorOf error_of) {
  return MakeForceSeries(count, status_of, error_of);
}

// Accurate with one estimate in ten at 3 sigma: error 0.3 N outside, 0.05 N inside.
double TenthOutside(int64_t k) { return k % 10 == 0 ? 0.3 : 0.05; }

// 10 s airborne from the first estimate: VALID and 10 sigma off for 5 s, not
// VALID for 2 s, then VALID and accurate. From 5 s: 3000 of 5000 VALID
// (0.6), MAE (300 x 0.3 + 2700 x 0.05) / 3000 = 0.075 N, share 0.9 (the
// band's edge, met); the first 2 s window holds 2000 VALID, none inside: 0.
TEST(MismatchTargets, ValidShareFromFiveSecondsAndTheFiguresOfTheValidOnes) {
  const Series s = Make(
      10000, [](int64_t k) -> int32_t { return k < 5000 || k >= 7000 ? kStatusValid : 0; },
      [](int64_t k) { return k < 5000 ? 1.0 : TenthOutside(k); });
  const MismatchTargets targets;
  const MismatchTargetFigures f = EvaluateMismatchTargets(s.forces, s.truth, -1, targets);
  EXPECT_EQ(f.estimates, 5000);
  EXPECT_DOUBLE_EQ(f.valid_share, 0.6);
  EXPECT_NEAR(f.valid_mae_n, 0.075, 1e-12);
  EXPECT_DOUBLE_EQ(f.two_sigma_share, 0.9);
  EXPECT_DOUBLE_EQ(f.worst_window_share, 0.0);
  const TargetMisses m = JudgeMismatchTargets(f, targets);
  EXPECT_TRUE(m.valid_share);
  EXPECT_FALSE(m.mae);
  EXPECT_FALSE(m.two_sigma_share);
  EXPECT_TRUE(m.window);
}

// A ground phase: 3 s on the ground (VALID, 10 sigma off) before lift-off,
// then one in ten outside with a 0.5 s block all outside at 6.0-6.5 s. From
// lift-off the worst window holds the whole block: (1500 - 150) / 2000 =
// 0.675; the ground phase is not judged. From the first estimate instead it
// is (share 0). The figures start 5 s after lift-off (8 s): 2000 estimates,
// MAE (200 x 0.3 + 1800 x 0.05) / 2000 = 0.075 N, share 0.9.
TEST(MismatchTargets, WorstWindowCountsFromLiftOff) {
  const Series s = Make(
      10000, [](int64_t) -> int32_t { return kStatusValid; },
      [](int64_t k) { return k < 3000 || (k >= 6000 && k < 6500) ? 1.0 : TenthOutside(k); });
  const MismatchTargets targets;
  const int64_t liftoff_utime = 1000000 + 3000 * 1000;
  const MismatchTargetFigures f = EvaluateMismatchTargets(s.forces, s.truth, liftoff_utime, targets);
  EXPECT_DOUBLE_EQ(f.worst_window_share, 0.675);
  EXPECT_EQ(f.estimates, 2000);
  EXPECT_DOUBLE_EQ(f.valid_share, 1.0);
  EXPECT_NEAR(f.valid_mae_n, 0.075, 1e-12);
  EXPECT_DOUBLE_EQ(f.two_sigma_share, 0.9);
  const TargetMisses m = JudgeMismatchTargets(f, targets);
  EXPECT_TRUE(m.window);  // 0.675 < 0.80
  EXPECT_FALSE(m.valid_share || m.mae || m.two_sigma_share);
  EXPECT_DOUBLE_EQ(EvaluateMismatchTargets(s.forces, s.truth, -1, targets).worst_window_share, 0.0);
}

// Never VALID after 5 s: share 0, MAE and 2-sigma share NaN (every target
// missed but the window's, which has no VALID estimate to judge).
TEST(MismatchTargets, NothingValidMissesEveryTargetButTheWindow) {
  const Series s = Make(
      10000, [](int64_t) -> int32_t { return kStatusModelMismatch; }, [](int64_t) { return 1.0; });
  const MismatchTargetFigures f = EvaluateMismatchTargets(s.forces, s.truth, -1, MismatchTargets());
  EXPECT_DOUBLE_EQ(f.valid_share, 0.0);
  EXPECT_TRUE(std::isnan(f.valid_mae_n));
  EXPECT_TRUE(std::isnan(f.two_sigma_share));
  EXPECT_DOUBLE_EQ(f.worst_window_share, 1.0);
  const TargetMisses m = JudgeMismatchTargets(f, MismatchTargets());
  EXPECT_TRUE(m.valid_share && m.mae && m.two_sigma_share);
  EXPECT_FALSE(m.window);
}

// The row over seeds: mean and worst seed per figure, the misses per target.
TEST(MismatchTargets, TableRowGivesMeanWorstSeedAndMissesPerTarget) {
  MismatchTargetFigures a;
  a.valid_share = 0.6;
  a.valid_mae_n = 0.075;
  a.two_sigma_share = 0.9;
  a.worst_window_share = 0.0;
  MismatchTargetFigures b;  // nothing VALID
  b.valid_share = 0.0;
  b.worst_window_share = 1.0;
  EXPECT_EQ(MismatchTargetsTableRow("case", {a, b}, MismatchTargets()),
            "| case | 2 | 0.300 (0.000) | 0.075 (none VALID) | 0.900 (none VALID) | 0.500 (0.000) | "
            "NOT met: VALID 2/2, MAE 1/2, 2-sigma 1/2, window 1/2 |\n");
  a.valid_share = 0.85;
  MismatchTargetFigures c = a;
  c.two_sigma_share = 0.97;
  c.worst_window_share = 0.9;
  a.worst_window_share = 0.85;
  // The 2-sigma share's worst is the one farther from the band's middle 0.94: 0.90 (0.04 off), not 0.97 (0.03).
  EXPECT_EQ(MismatchTargetsTableRow("ok", {a, c}, MismatchTargets()),
            "| ok | 2 | 0.850 (0.850) | 0.075 (0.075) | 0.935 (0.900) | 0.875 (0.850) | met |\n");
}

}  // namespace
}  // namespace birotor
