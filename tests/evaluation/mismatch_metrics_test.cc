// The model-consistency figures (evaluation/mismatch_metrics.h) on hand-made
// series: the raise time, the VALID estimates before it, the 2-sigma share
// after the settling time and the worst 2 s window of VALID estimates with
// its 200-estimate floor (docs/mismatch.md).
#include "evaluation/mismatch_metrics.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/evaluation/synthetic_force_series.h"

namespace birotor {
namespace {

// 1 kHz estimates over duration_s (tests/evaluation/synthetic_force_series.h).
using Series = SyntheticForceSeries;
template <typename StatusOf, typename ErrorOf>
Series Make(double duration_s, StatusOf status_of, ErrorOf error_of) {
  return MakeForceSeries(static_cast<int64_t>(duration_s * 1000), status_of, error_of);
}

MismatchEvalOptions Options() {
  MismatchEvalOptions o;
  o.settle_s = 3.0;
  return o;
}

// VALID and 1 N off (10 sigma) for the first 0.3 s, then MODEL_MISMATCH to
// the end: raised at 0.3 s with 300 VALID estimates before it, and the
// windows over the start judge those 300 (>= 200): share 0.
TEST(MismatchMetrics, ValidBeforeASlowRaiseIsTheWorstWindow) {
  const Series s = Make(
      5.0, [](int64_t k) -> int32_t { return k < 300 ? kStatusValid : kStatusModelMismatch; },
      [](int64_t k) { return k < 300 ? 1.0 : 0.05; });
  const MismatchEvalResult r = EvaluateMismatch(s.forces, s.truth, Options());
  EXPECT_DOUBLE_EQ(r.mismatch_raised_s, 0.3);
  EXPECT_EQ(r.valid_before_raise, 300);
  EXPECT_EQ(r.mismatch_estimates, 4700);
  EXPECT_DOUBLE_EQ(r.valid_share, 300.0 / 5000.0);
  EXPECT_DOUBLE_EQ(r.worst_valid_window_share, 0.0);
  EXPECT_NEAR(r.mae_after_settle_n[0], 0.05, 1e-12);  // from 3 s: the accurate part
  EXPECT_DOUBLE_EQ(r.share_after_settle, 1.0);
  const std::string row = MismatchTableRow("case", "ekf", r);
  EXPECT_EQ(row, "| case | ekf | 0.050 / 0.050 | 1.000 | 0.300 | 300 | 0.060 | 0.000 | 0 | 0 |\n");
}

// A raise after 10 VALID estimates: no 2 s window holds 200 VALID ones until
// the estimate is VALID and accurate again (from 2.5 s), so the worst share
// is that of the accurate part; a deficit and a fault are counted.
TEST(MismatchMetrics, AFastRaiseLeavesTooFewValidEstimatesToJudge) {
  const Series s = Make(
      5.0,
      [](int64_t k) -> int32_t {
        if (k < 10) return kStatusValid;
        if (k < 2500) return kStatusModelMismatch;
        return k < 2600 ? kStatusValid | kStatusThrustDeficit | kStatusRotor1Fault : kStatusValid;
      },
      [](int64_t k) { return k < 10 ? 1.0 : (k % 10 == 0 ? 0.3 : 0.05); });  // 1 in 10 outside 2 sigma
  const MismatchEvalResult r = EvaluateMismatch(s.forces, s.truth, Options());
  EXPECT_DOUBLE_EQ(r.mismatch_raised_s, 0.01);
  EXPECT_EQ(r.valid_before_raise, 10);
  EXPECT_DOUBLE_EQ(r.worst_valid_window_share, 0.9);
  EXPECT_EQ(r.thrust_deficit, 100);
  EXPECT_EQ(r.rotor_fault, 100);
  EXPECT_DOUBLE_EQ(r.share_after_settle, 0.9);
}

TEST(MismatchMetrics, NeverRaisedPrintsNeverAndNoCount) {
  const Series s = Make(
      3.0, [](int64_t) -> int32_t { return kStatusValid; }, [](int64_t) { return 0.05; });
  const MismatchEvalResult r = EvaluateMismatch(s.forces, s.truth, Options());
  EXPECT_DOUBLE_EQ(r.mismatch_raised_s, -1.0);
  EXPECT_EQ(r.valid_before_raise, -1);
  EXPECT_DOUBLE_EQ(r.valid_share, 1.0);
  EXPECT_DOUBLE_EQ(r.worst_valid_window_share, 1.0);
  EXPECT_NE(MismatchTableRow("hover", "ekf", r).find("| never | - | 1.000 | 1.000 |"), std::string::npos);
}

}  // namespace
}  // namespace birotor
