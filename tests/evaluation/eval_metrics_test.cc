// Error statistics, fault detection delay and false alarms on hand-made series.
#include "evaluation/eval_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace birotor {
namespace {

TruthSample Truth(int64_t utime, double f1, double f2, double s2 = 1.0) {
  TruthSample t;
  t.utime = utime;
  t.force_n[0] = f1;
  t.force_n[1] = f2;
  t.thrust_scale[1] = s2;
  return t;
}

ForceEstimate Estimate(int64_t utime, double f1, double f2, int32_t status = kStatusValid, double s2 = 1.0) {
  ForceEstimate e;
  e.utime = utime;
  e.force_n[0] = f1;
  e.force_n[1] = f2;
  e.thrust_scale[1] = s2;
  e.status = status;
  return e;
}

TEST(EvalMetricsTest, ErrorStatisticsPerRotor) {
  std::vector<TruthSample> truth;
  std::vector<ForceEstimate> forces;
  for (int k = 0; k < 100; ++k) {
    truth.push_back(Truth(k * 1000, 20.0, 20.0));
    // Rotor 1 error k/100 (0 .. 0.99), rotor 2 exact.
    forces.push_back(Estimate(k * 1000, 20.0 + k / 100.0, 20.0));
  }
  forces.push_back(Estimate(999'999, 1, 1));  // no truth at that utime
  EvalOptions options;
  options.warmup_s = 0;
  const EvalResult r = Evaluate(forces, truth, {}, options);
  EXPECT_EQ(r.paired, 100);
  EXPECT_EQ(r.unpaired, 1);
  EXPECT_NEAR(r.rotor[0].mae_n, 0.495, 1e-12);
  EXPECT_NEAR(r.rotor[0].max_n, 0.99, 1e-12);
  EXPECT_NEAR(r.rotor[0].p95_n, 0.94, 1e-12);
  EXPECT_NEAR(r.rotor[0].rmse_n, std::sqrt(0.328350), 1e-6);
  EXPECT_EQ(r.rotor[1].mae_n, 0.0);
  EXPECT_EQ(r.step_rotor, 0);
  EXPECT_EQ(r.false_alarms, 0);
}

TEST(EvalMetricsTest, FaultDelayScaleErrorFalseAlarmsAndExclusion) {
  std::vector<TruthSample> truth;
  std::vector<ForceEstimate> forces;
  for (int k = 0; k < 1000; ++k) {
    const int64_t t = k * 1000;
    const double s2 = k < 500 ? 1.0 : 0.75;
    truth.push_back(Truth(t, 20, 20 * s2, s2));
    int32_t status = kStatusValid;
    if (k == 100) status |= kStatusRotor1Fault;              // false alarm (truth s1 = 1)
    if (k >= 520) status |= kStatusRotor2Fault;              // detected 20 ms after the step
    const double error = (k >= 300 && k < 310) ? 5.0 : 0.0;  // a fault transient
    forces.push_back(Estimate(t, 20 + error, 20 * s2, status, k >= 600 ? 0.76 : 1.0));
  }
  EvalOptions options;
  options.warmup_s = 0;
  const EvalResult r = Evaluate(forces, truth, {300'000}, options);
  EXPECT_EQ(r.step_rotor, 2);
  EXPECT_NEAR(r.step_time_s, 0.5, 1e-12);
  EXPECT_NEAR(r.detection_delay_s, 0.020, 1e-12);
  EXPECT_NEAR(r.scale_error_after_step, 0.01, 1e-12);
  EXPECT_EQ(r.false_alarms, 1);
  EXPECT_NEAR(r.rotor[0].mae_n, 0.05, 1e-12);
  EXPECT_EQ(r.mae_outside_faults_n[0], 0.0);  // 300..499 ms excluded
}

TEST(EvalMetricsTest, NonFiniteEstimatesAreCountedAndScoreInfinite) {
  std::vector<TruthSample> truth = {Truth(0, 1, 1), Truth(1000, 1, 1)};
  std::vector<ForceEstimate> forces = {Estimate(0, 1, 1), Estimate(1000, std::nan(""), 1)};
  EvalOptions options;
  options.warmup_s = 0;
  const EvalResult r = Evaluate(forces, truth, {}, options);
  EXPECT_EQ(r.nonfinite, 1);
  EXPECT_TRUE(std::isinf(r.rotor[0].max_n));
}

}  // namespace
}  // namespace birotor
