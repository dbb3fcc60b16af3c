// The two body-mass hypotheses (estimator/parameter_hypotheses.h): the
// Savage-Dickey probability of a payload and the average over both, against
// the formulas worked by hand.
#include "estimator/parameter_hypotheses.h"

#include <gtest/gtest.h>

#include <cmath>

namespace birotor {
namespace {

TEST(BodyMassHypotheses, BeforeAnyDataThePriorProbability) {
  // scale 1 with the prior's sigma: B01 = 1, P(H1) = p.
  EXPECT_NEAR(ChangedParameterProbability(1.0, 0.15, 0.15, 0.1), 0.1, 1e-15);
  EXPECT_NEAR(ChangedParameterProbability(1.0, 0.15, 0.15, 0.5), 0.5, 1e-15);
  EXPECT_EQ(ChangedParameterProbability(1.3, 0.01, 0.15, 1.0), 1.0);  // p = 1: always a payload
}

TEST(BodyMassHypotheses, DataThatPinsTheFileMassLowersIt) {
  // r = 1 +- 0.01: B01 = 0.15 / 0.01 = 15, odds of H1 (0.1 / 0.9) / 15, P = 1 / 136.
  EXPECT_NEAR(ChangedParameterProbability(1.0, 0.01, 0.15, 0.1), 1.0 / 136.0, 1e-12);
}

TEST(BodyMassHypotheses, DataThatPinsAPayloadRaisesIt) {
  // r = 1.1 +- 0.027 (a 10 % payload, offsets' prior alone): z = 3.70,
  // B01 = (0.15 / 0.027) exp(-z^2 / 2) = 0.0057, P(H1) = 1 / (1 + 9 B01) = 0.951.
  const double z = 0.1 / 0.027;
  const double b01 = (0.15 / 0.027) * std::exp(-0.5 * z * z);
  EXPECT_NEAR(ChangedParameterProbability(1.1, 0.027, 0.15, 0.1), 1.0 / (1.0 + 9.0 * b01), 1e-12);
  EXPECT_GT(ChangedParameterProbability(1.1, 0.027, 0.15, 0.1), 0.95);
  // Far beyond: no overflow, P(H1) exactly 1 to the double.
  EXPECT_EQ(ChangedParameterProbability(1.15, 1e-4, 0.15, 0.1), 1.0);
  EXPECT_LT(ChangedParameterProbability(1.0, 0.0, 0.15, 0.1), 1e-8);  // sigma 0 at the file: H0 all but certain
}

TEST(BodyMassHypotheses, TheFileHypothesisIsTheGaussianConditionedOnTheFileMass) {
  // x = 20 N, var 0.25, cov(x, r) = 0.02, r = 1.1, var r = 0.01: gain 2,
  // x0 = 20 + 2 (1 - 1.1) = 19.8, var0 = 0.25 - 0.04 = 0.21.
  const HypothesesAverage h0 = AverageOverHypotheses(20.0, 0.25, 0.02, 1.1, 0.01, 0.0);
  EXPECT_NEAR(h0.value, 19.8, 1e-12);
  EXPECT_NEAR(h0.variance, 0.21, 1e-12);
  const HypothesesAverage h1 = AverageOverHypotheses(20.0, 0.25, 0.02, 1.1, 0.01, 1.0);
  EXPECT_NEAR(h1.value, 20.0, 1e-12);
  EXPECT_NEAR(h1.variance, 0.25, 1e-12);
  // w1 = 0.25: mean 0.75 x 19.8 + 0.25 x 20 = 19.85, variance
  // 0.75 x 0.21 + 0.25 x 0.25 + 0.75 x 0.25 x 0.2^2 = 0.2275.
  const HypothesesAverage mixed = AverageOverHypotheses(20.0, 0.25, 0.02, 1.1, 0.01, 0.25);
  EXPECT_NEAR(mixed.value, 19.85, 1e-12);
  EXPECT_NEAR(mixed.variance, 0.2275, 1e-12);
}

TEST(BodyMassHypotheses, AFrozenMassLeavesTheEstimate) {
  const HypothesesAverage a = AverageOverHypotheses(20.0, 0.25, 0.0, 1.1, 0.0, 0.5);
  EXPECT_EQ(a.value, 20.0);
  EXPECT_EQ(a.variance, 0.25);
}

}  // namespace
}  // namespace birotor
