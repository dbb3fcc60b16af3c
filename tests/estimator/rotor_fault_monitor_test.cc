// Rotor faults and the thrust deficit (estimator/rotor_fault_monitor.h) with
// the EkfOptions defaults: asymmetry 0.1 (cleared below 0.07), deficit 0.95
// (cleared above 0.97), 3 sigma; the persistence set to 10 ms here (default
// 2 ms) so that its count shows.
#include "estimator/rotor_fault_monitor.h"

#include <gtest/gtest.h>

#include "samples/samples.h"

namespace birotor {
namespace {

const Eigen::Matrix2d kSure = Eigen::Matrix2d::Identity() * 1e-6;  // std(mu) = 1e-3

// The monitor's facts alone, composed (estimator/force_status.h).
int32_t Bits(const RotorFaultMonitor& monitor) {
  ForceStatusFacts facts;
  monitor.FillFacts(&facts.filter);
  return ComposeForceStatus(facts);
}

EkfOptions TenMilliseconds() {
  EkfOptions options;
  options.fault_persistence_s = 0.01;
  return options;
}

// Rotor 2 at 0.8 of rotor 1: d - 3 std(d) = 0.2 - 0.0042 > 0.1. Flagged once
// it held for 10 ms (at 10 ms, not at 9), cleared at once below 0.07.
TEST(RotorFaultMonitorTest, AWeakRotorIsFlaggedAfterThePersistenceAndClears) {
  RotorFaultMonitor monitor{TenMilliseconds()};
  for (int64_t t = 0; t < 10000; t += 1000) {
    monitor.Update(t, Eigen::Vector2d(1.0, 0.8), kSure);
    EXPECT_EQ(Bits(monitor), 0) << t;
  }
  monitor.Update(10000, Eigen::Vector2d(1.0, 0.8), kSure);
  EXPECT_EQ(Bits(monitor), kStatusRotor2Fault);
  // 0.08 + 0.0042 is not below 0.07: held (hysteresis); 0.05 clears.
  monitor.Update(11000, Eigen::Vector2d(1.0, 0.92), kSure);
  EXPECT_EQ(Bits(monitor), kStatusRotor2Fault);
  monitor.Update(12000, Eigen::Vector2d(1.0, 0.95), kSure);
  EXPECT_EQ(Bits(monitor), 0);
}

// An uncertain difference is no fault: std(mu) = 0.1 each, std(d) = 0.14,
// d - 3 std(d) < 0.1 for d = 0.2. Correlation counts: with P12 = P11 the
// difference is known exactly and the same d is a fault.
TEST(RotorFaultMonitorTest, TheDifferenceIsJudgedWithItsSigma) {
  RotorFaultMonitor loose{TenMilliseconds()};
  const Eigen::Matrix2d independent = Eigen::Matrix2d::Identity() * 0.01;
  for (int64_t t = 0; t <= 20000; t += 1000) loose.Update(t, Eigen::Vector2d(0.8, 1.0), independent);
  EXPECT_EQ(Bits(loose), 0);
  RotorFaultMonitor correlated{TenMilliseconds()};
  const Eigen::Matrix2d same = Eigen::Matrix2d::Constant(0.01);
  for (int64_t t = 0; t <= 20000; t += 1000) correlated.Update(t, Eigen::Vector2d(0.8, 1.0), same);
  EXPECT_EQ(Bits(correlated), kStatusRotor1Fault);
}

// Both rotors at 0.9: the stronger one's 0.9 + 0.003 < 0.95 is a deficit, not
// a rotor fault; an interruption restarts the persistence; Reset forgets it.
TEST(RotorFaultMonitorTest, ASharedDeficitIsNotARotorFault) {
  RotorFaultMonitor monitor{TenMilliseconds()};
  monitor.Update(0, Eigen::Vector2d(0.9, 0.9), kSure);
  monitor.Update(5000, Eigen::Vector2d(1.0, 1.0), kSure);  // interrupted
  monitor.Update(6000, Eigen::Vector2d(0.9, 0.9), kSure);
  monitor.Update(15000, Eigen::Vector2d(0.9, 0.9), kSure);
  EXPECT_EQ(Bits(monitor), 0);
  monitor.Update(16000, Eigen::Vector2d(0.9, 0.9), kSure);
  EXPECT_EQ(Bits(monitor), kStatusThrustDeficit);
  monitor.Reset();
  EXPECT_EQ(Bits(monitor), 0);
}

}  // namespace
}  // namespace birotor
