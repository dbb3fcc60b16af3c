// Attitude before altitude (rotor_allocation.h): within the limits the law's
// forces pass unchanged; beyond them the difference f2 - f1 is kept and the
// total gives way; only a difference beyond reach is clipped.
#include "controller/rotor_allocation.h"

#include <gtest/gtest.h>

namespace birotor {
namespace {

TEST(RotorAllocationTest, WithinLimitsUnchanged) {
  const double max[2] = {66.24, 66.24};  // c_T omega_max^2 = 4.6e-5 x 1200^2
  const RotorAllocation a = AllocateAttitudeFirst(44.8, 2.0, max);
  EXPECT_DOUBLE_EQ(a.force_n[0], 21.4);
  EXPECT_DOUBLE_EQ(a.force_n[1], 23.4);
  EXPECT_FALSE(a.total_limited || a.difference_limited);
}

TEST(RotorAllocationTest, WeakRotorKeepsTheTorqueAndTheTotalGivesWay) {
  // Rotor 2 at 30 %: 19.87 N at most; the law asks 44.8 N with f2 - f1 = 0.
  const double max[2] = {66.24, 0.3 * 66.24};
  const RotorAllocation a = AllocateAttitudeFirst(44.8, 0.0, max);
  EXPECT_DOUBLE_EQ(a.force_n[0], 0.3 * 66.24);  // level: both at the weak rotor's maximum
  EXPECT_DOUBLE_EQ(a.force_n[1], 0.3 * 66.24);
  EXPECT_TRUE(a.total_limited);
  EXPECT_FALSE(a.difference_limited);
}

TEST(RotorAllocationTest, DifferenceBeyondReachIsClipped) {
  const double max[2] = {10.0, 10.0};
  const RotorAllocation a = AllocateAttitudeFirst(5.0, 30.0, max);
  EXPECT_DOUBLE_EQ(a.force_n[0], 0.0);
  EXPECT_DOUBLE_EQ(a.force_n[1], 10.0);
  EXPECT_TRUE(a.difference_limited);
}

}  // namespace
}  // namespace birotor
