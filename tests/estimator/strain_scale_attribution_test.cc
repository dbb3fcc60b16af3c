// What learned strain scales are (estimator/strain_scale_attribution.h): the
// evidence each single change makes is attributed to it, two changes at
// once are not explained, and a payload is told from a stiffness by the arm
// mode.
#include "estimator/strain_scale_attribution.h"

#include <gtest/gtest.h>

#include <cmath>

namespace birotor {
namespace {

constexpr double kScaleStd = 0.01;  // the learned ln g_i's sigma [1]
constexpr double kModeStd = 0.005;  // the mode's log-shift sigma [1]

ScaleAttributionOptions Options() {
  ScaleAttributionOptions o;
  o.tip_mass_mode_slope = -0.4;  // the reference birotor's hover mode over ln m_p, about
  o.explained_distance2 = 6.0;
  return o;
}

// The evidence of learned scales g_1, g_2 and a mode shifted by b.
ScaleEvidence Evidence(double g1, double g2, double mode_shift) {
  ScaleEvidence e;
  e.log_scale[0] = std::log(g1);
  e.log_scale[1] = std::log(g2);
  e.log_scale_var[0] = e.log_scale_var[1] = kScaleStd * kScaleStd;
  e.mode_shift = mode_shift;
  e.mode_shift_var = kModeStd * kModeStd;
  return e;
}

TEST(StrainScaleAttribution, TheFilesVehicleIsTheFiles) {
  const ScaleAttribution a = AttributeScales(Evidence(1.0, 1.0, 0.0), Options());
  EXPECT_GT(a.of(ScaleChange::kNone), 0.8);
  EXPECT_TRUE(a.explained);
}

TEST(StrainScaleAttribution, AStifferArmPairMovesTheModeAsTheScalesSay) {
  // k 15 % up: g = 1 / 1.15 on both arms, the mode up by half of ln 1.15.
  const double kappa = std::log(1.15);
  const ScaleAttribution a = AttributeScales(Evidence(1.0 / 1.15, 1.0 / 1.15, 0.5 * kappa), Options());
  EXPECT_GT(a.of(ScaleChange::kStiffness), 0.95);
  EXPECT_LT(a.of(ScaleChange::kCommonScale), 0.05);
  EXPECT_TRUE(a.explained);
}

TEST(StrainScaleAttribution, APayloadScalesBothGaugesAndLeavesTheModeAlone) {
  // Body +10 % with the tips: the accelerometer weighs the total force
  // against the file's mass, so both scales read about 8 % high.
  const ScaleAttribution a = AttributeScales(Evidence(1.08, 1.08, 0.0), Options());
  EXPECT_GT(a.of(ScaleChange::kCommonScale), 0.6);  // raised from 0.3 on (scale_attribution_payload_weight)
  EXPECT_LT(a.of(ScaleChange::kStiffness), 0.2);
}

TEST(StrainScaleAttribution, OneGaugesScaleIsThatGauge) {
  const ScaleAttribution a = AttributeScales(Evidence(0.7, 1.0, 0.0), Options());
  EXPECT_GT(a.of(ScaleChange::kGauge1), 0.95);
  const ScaleAttribution b = AttributeScales(Evidence(1.0, 0.7, 0.0), Options());
  EXPECT_GT(b.of(ScaleChange::kGauge2), 0.95);
}

TEST(StrainScaleAttribution, AHeavierTipLowersTheModeWithTheScalesAtOne) {
  // m_p 20 % up: the mode down by 0.4 ln 1.2, g unchanged.
  const ScaleAttribution a = AttributeScales(Evidence(1.0, 1.0, -0.4 * std::log(1.2)), Options());
  EXPECT_GT(a.of(ScaleChange::kTipMass), 0.9);
}

TEST(StrainScaleAttribution, TwoChangesAtOnceAreNotExplained) {
  // One gauge at 0.7 and a payload of 10 %: neither alone gives both the
  // common part and the difference.
  const ScaleAttribution a = AttributeScales(Evidence(0.7 * 1.1, 1.1, 0.0), Options());
  EXPECT_FALSE(a.explained);
  EXPECT_GT(a.best_distance2, 6.0);
}

TEST(StrainScaleAttribution, WeightsSumToOneAndWideScalesLeaveTheFile) {
  // Scales the flight has not pinned (sigma 0.1) that wander by 5 %: the file
  // stays the likeliest, nothing is raised by them.
  ScaleEvidence e = Evidence(0.95, 0.95, 0.0);
  e.log_scale_var[0] = e.log_scale_var[1] = 0.1 * 0.1;
  e.mode_shift_var = 0.06 * 0.06;
  const ScaleAttribution a = AttributeScales(e, Options());
  double sum = 0.0;
  for (const double w : a.weight) sum += w;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_GT(a.of(ScaleChange::kNone), 0.5);
  EXPECT_LT(a.of(ScaleChange::kCommonScale), 0.3);
}

}  // namespace
}  // namespace birotor
