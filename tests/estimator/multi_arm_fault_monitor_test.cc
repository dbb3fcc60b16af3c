// The N-rotor fault monitor (estimator/multi_arm_fault_monitor.h) on
// hand-made thrust scales: a rotor's fault after fault_persistence_s, and a
// second rotor's within fault_second_rotor_window_s of it only after
// fault_second_rotor_persistence_s; then the flight it is for (a 25 % loss
// on the trirotor's rotor 3, seeds 1 and 5).
#include "estimator/multi_arm_fault_monitor.h"

#include <gtest/gtest.h>

#include "evaluation/eval_runner.h"
#include "evaluation/multi_arm_accuracy.h"
#include "multi_arm_source_files.h"

namespace birotor {
namespace {

constexpr int64_t kMs = 1000;
constexpr double kStd = 0.005;  // each thrust scale's sigma [1]

MultiArmFaultMonitor::ScaleMatrix Covariance() {
  MultiArmFaultMonitor::ScaleMatrix p = MultiArmFaultMonitor::ScaleMatrix::Zero();
  for (int i = 0; i < kMaxArms; ++i) p(i, i) = kStd * kStd;
  return p;
}

// mu = 1 on every rotor but `low` ones at 0.7, one update per millisecond
// from t0 for `ms` milliseconds; returns the last update's time.
int64_t Hold(MultiArmFaultMonitor* monitor, int64_t t0, int ms, int low_a, int low_b = -1) {
  MultiArmFaultMonitor::ScaleVector mu = MultiArmFaultMonitor::ScaleVector::Ones();
  if (low_a >= 0) mu(low_a) = 0.7;
  if (low_b >= 0) mu(low_b) = 0.7;
  int64_t t = t0;
  for (int k = 0; k < ms; ++k, t += kMs) monitor->Update(t, 3, mu, Covariance());
  return t - kMs;
}

// A lone loss is flagged after fault_persistence_s (2 ms: the third update).
TEST(MultiArmFaultMonitorTest, ALoneLossIsFlaggedAfterThePersistence) {
  MultiArmFaultMonitor monitor{EkfOptions()};
  Hold(&monitor, 0, 2, 2);
  EXPECT_FALSE(monitor.fault(2));
  Hold(&monitor, 2 * kMs, 1, 2);
  EXPECT_TRUE(monitor.fault(2));
  EXPECT_FALSE(monitor.fault(0));
  EXPECT_FALSE(monitor.fault(1));
}

// Rotor 3 flagged; 10 ms later rotor 2 dips for 5 ms (the transient's
// swing): not flagged. A dip of 7 ms is (6 ms persistence), and outside
// the 50 ms window 3 updates are enough again.
TEST(MultiArmFaultMonitorTest, ASecondRotorWithinTheWindowNeedsTheLongerPersistence) {
  MultiArmFaultMonitor monitor{EkfOptions()};
  int64_t t = Hold(&monitor, 0, 3, 2);
  ASSERT_TRUE(monitor.fault(2));
  t = Hold(&monitor, t + kMs, 10, 2);
  t = Hold(&monitor, t + kMs, 5, 2, 1);
  EXPECT_FALSE(monitor.fault(1));
  t = Hold(&monitor, t + kMs, 2, 2);
  t = Hold(&monitor, t + kMs, 7, 2, 1);
  EXPECT_TRUE(monitor.fault(1));
  MultiArmFaultMonitor later{EkfOptions()};
  t = Hold(&later, 0, 3, 2);
  t = Hold(&later, t + kMs, 60, 2);
  Hold(&later, t + kMs, 3, 2, 0);
  EXPECT_TRUE(later.fault(0));
}

// The trirotor, 25 % off rotor 3 at 5 s of thrust_loss, seeds 1 and 5.
// Before the second-rotor persistence: flagged after 10 ms, then rotor 2
// falsely for 3 estimates (16-18 ms after the loss) on both seeds. Measured
// now: 10 ms, no false alarm. Asserted: within 15 ms, none.
TEST(MultiArmFaultMonitorTest, TheTrirotorsLossOnRotor3FlagsNoOtherRotor) {
  for (int seed : {1, 5}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const MultiArmAccuracy r = RunMultiArmAccuracy(
        Vehicle("trirotor"),
        ScenarioFor(
            "thrust_loss",
            {"scenario.seed=" + std::to_string(seed), "faults.thrust_steps=[{time_s: 5.0, rotor: 3, scale: 0.75}]"}, 3),
        Config(), EvalOptions());
    EXPECT_EQ(r.step_rotor, 3);
    EXPECT_LE(r.detection_delay_s, 0.015);
    EXPECT_EQ(r.false_alarms, 0);
  }
}

}  // namespace
}  // namespace birotor
