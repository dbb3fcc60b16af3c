// Attitude before altitude (rotor_allocation.h): within the limits the law's
// forces pass unchanged; beyond them the difference f2 - f1 is kept and the
// total gives way; only a difference beyond reach is clipped. The flare of a
// descent the rotors cannot stop (FlareForcesFor): the extra thrust of the
// strong rotor that brings the tilt to the budget at touchdown.
#include "controller/rotor_allocation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

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

// The reference vehicle at 70 % loss on rotor 2 (config/reference_vehicle.yaml):
// J_eff = J + 2 m_p L^2 = 0.05 + 2 x 0.28812 x 0.25^2 = 0.086015 kg m^2,
// rotor 1 66.24 N at most, rotor 2 0.3 x 66.24 = 19.872 N.
FlareLimits ReferenceFlareLimits(double tilt_budget_rad) {
  FlareLimits limits;
  limits.tilt_budget_rad = tilt_budget_rad;
  limits.min_time_to_go_s = 0.035;  // tau_m
  limits.pitch_inertia_kg_m2 = 0.05 + 2.0 * 0.28812 * 0.25 * 0.25;
  limits.arm_length_m = 0.25;
  limits.max_force_n[0] = 66.24;
  limits.max_force_n[1] = 0.3 * 66.24;
  return limits;
}

TEST(FlareForcesTest, ExtraThrustReachesTheBudgetAtTouchdown) {
  // The brief's figure: 3 N extra on rotor 1 for the last 0.1 s tilts
  // L dF t^2 / (2 J_eff) = 0.25 x 3 x 0.01 / (2 x 0.086015) = 0.0436 rad and
  // takes dF t / m = 3 x 0.1 / 4.576 = 0.066 m/s off the touchdown speed. So
  // 0.1 m above the ground at 1 m/s, level and still, a 0.0436 rad budget
  // asks for those 3 N.
  FlareState state;
  state.height_m = 0.1;
  state.sink_rate_m_s = 1.0;
  const FlareForces f = FlareForcesFor(state, ReferenceFlareLimits(0.25 * 3.0 * 0.01 / (2.0 * 0.086015)));
  EXPECT_NEAR(f.time_to_go_s, 0.1, 1e-12);
  EXPECT_NEAR(f.extra_force_n, 3.0, 1e-9);
  // The weak rotor 2 at its maximum, rotor 1 3 N above it: f2 - f1 = -3 N
  // (phi'' = L (f2 - f1) / J_eff < 0, towards the weak side).
  EXPECT_NEAR(f.total_force_n, 2.0 * 0.3 * 66.24 + 3.0, 1e-9);
  EXPECT_NEAR(f.force_difference_n, -3.0, 1e-9);
  const double max[2] = {66.24, 0.3 * 66.24};
  const RotorAllocation a = AllocateAttitudeFirst(f.total_force_n, f.force_difference_n, max);
  EXPECT_NEAR(a.force_n[0], 0.3 * 66.24 + 3.0, 1e-9);
  EXPECT_NEAR(a.force_n[1], 0.3 * 66.24, 1e-9);
}

TEST(FlareForcesTest, TiltAndRateAlreadyTowardsTheWeakSideUseTheBudget) {
  FlareState state;
  state.height_m = 0.1;
  state.sink_rate_m_s = 1.0;
  // Rotor 1 strong: the flare tilts phi negative. phi = -0.03 rad and
  // phi_dot = -0.2 rad/s reach -0.05 rad in t_go = 0.1 s on their own:
  // budget 0.08 leaves 0.03 rad, dF = 2 x 0.086015 x 0.03 / (0.25 x 0.01) = 2.064 N.
  state.tilt_rad = -0.03;
  state.pitch_rate_rad_s = -0.2;
  EXPECT_NEAR(FlareForcesFor(state, ReferenceFlareLimits(0.08)).extra_force_n, 2.0 * 0.086015 * 0.03 / 0.0025, 1e-4);
  // Already past the budget: no flare thrust (never pushed back level here;
  // that is the law's job).
  state.tilt_rad = -0.1;
  EXPECT_EQ(FlareForcesFor(state, ReferenceFlareLimits(0.08)).extra_force_n, 0.0);
}

TEST(FlareForcesTest, LastMomentIsLimitedByTheMotorLagAndTheStrongRotor) {
  FlareLimits limits = ReferenceFlareLimits(0.08);
  FlareState state;
  state.height_m = 0.001;  // t_go 1 ms, taken as tau_m = 35 ms
  state.sink_rate_m_s = 1.0;
  const FlareForces f = FlareForcesFor(state, limits);
  EXPECT_DOUBLE_EQ(f.time_to_go_s, 0.035);
  EXPECT_NEAR(f.extra_force_n, 2.0 * 0.086015 * 0.08 / (0.25 * 0.035 * 0.035), 1e-3);  // 44.9 N
  // ... and never more than the strong rotor has above the weak one.
  limits.max_force_n[0] = 30.0;
  EXPECT_NEAR(FlareForcesFor(state, limits).extra_force_n, 30.0 - 0.3 * 66.24, 1e-9);
}

TEST(FlareForcesTest, RotorTwoStrongTiltsPositiveAndBadStateAsksNothing) {
  FlareLimits limits = ReferenceFlareLimits(0.0436);
  std::swap(limits.max_force_n[0], limits.max_force_n[1]);
  FlareState state;
  state.height_m = 0.1;
  state.sink_rate_m_s = 1.0;
  const FlareForces f = FlareForcesFor(state, limits);
  EXPECT_NEAR(f.force_difference_n, 2.0 * 0.086015 * 0.0436 / (0.25 * 0.01), 1e-9);  // +3.0 N: f2 > f1
  state.tilt_rad = std::nan("");
  const FlareForces bad = FlareForcesFor(state, limits);
  EXPECT_EQ(bad.extra_force_n, 0.0);
  EXPECT_NEAR(bad.total_force_n, 2.0 * 0.3 * 66.24, 1e-9);
}

}  // namespace
}  // namespace birotor
