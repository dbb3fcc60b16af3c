// HoverFeasibility (controller/hover_feasibility.h): hover lost from the
// efficiencies or from the sink, latched with its weak rotor, and the descent
// levelling first. The reference vehicle: c_T omega_max^2 = 4.6e-5 x 1200^2 =
// 66.24 N, weight 4.57624 x 9.81 = 44.89 N, so the bound on the weaker
// efficiency is 1.02 x 44.89 / (2 x 66.24) = 0.3457.
#include "controller/hover_feasibility.h"

#include <gtest/gtest.h>

namespace birotor {
namespace {

constexpr double kMaxRotorForceN = 4.6e-5 * 1200.0 * 1200.0;
constexpr double kWeightN = 4.57624 * 9.81;
constexpr double kDtS = 0.002;

// Runs periods of in until the phase is not kFeasible or seconds have passed; returns the time taken [s].
double RunUntilInfeasible(HoverFeasibility* f, const FeasibilityInputs& in, double seconds) {
  double t = 0.0;
  while (t < seconds && !f->infeasible()) {
    f->Update(in, kDtS);
    t += kDtS;
  }
  return t;
}

TEST(HoverFeasibilityTest, BoundIsTheFeasibilityMarginOverTwiceTheRotorMaximum) {
  const HoverFeasibility f(EfficiencyParams(), kMaxRotorForceN, kWeightN);
  EXPECT_NEAR(f.FeasibilityBound(), 0.3457, 1e-4);
}

TEST(HoverFeasibilityTest, LowEfficiencyLatchesAfterInfeasibleSAndHoldsWhenForceIsLost) {
  const EfficiencyParams params;
  HoverFeasibility f(params, kMaxRotorForceN, kWeightN);
  FeasibilityInputs in;
  in.efficiency[1] = 0.3;
  in.following_force = true;
  in.tilt_rad = 0.2;  // not level yet
  const double taken_s = RunUntilInfeasible(&f, in, 1.0);
  EXPECT_NEAR(taken_s, params.infeasible_s, 1.5 * kDtS);
  EXPECT_EQ(f.cause(), HoverFeasibility::Cause::kEfficiency);
  EXPECT_EQ(f.weak_rotor(), 1);
  EXPECT_EQ(f.phase(), HoverFeasibility::Phase::kLevelling);
  // FORCE unusable (MODEL_MISMATCH): the fallback decays e towards 1; the
  // latched weak rotor keeps 0.3 and the flight stays infeasible.
  in.following_force = false;
  in.efficiency[1] = 0.9;
  f.Update(in, kDtS);
  EXPECT_TRUE(f.infeasible());
  EXPECT_DOUBLE_EQ(f.weak_efficiency(), 0.3);
  EXPECT_DOUBLE_EQ(f.EfficiencyFor(1, 0.9), 0.3);
  EXPECT_DOUBLE_EQ(f.EfficiencyFor(0, 1.0), 1.0);
  // A usable FORCE is followed again, at most up to the bound.
  in.following_force = true;
  f.Update(in, kDtS);
  EXPECT_NEAR(f.weak_efficiency(), 0.3457, 1e-4);
  in.efficiency[1] = 0.28;
  f.Update(in, kDtS);
  EXPECT_DOUBLE_EQ(f.weak_efficiency(), 0.28);
}

TEST(HoverFeasibilityTest, DescendsOnceLevelAndCalm) {
  const EfficiencyParams params;
  HoverFeasibility f(params, kMaxRotorForceN, kWeightN);
  FeasibilityInputs in;
  in.efficiency[0] = 0.25;
  in.tilt_rad = 0.3;
  in.pitch_rate_rad_s = 0.0;
  RunUntilInfeasible(&f, in, 1.0);
  EXPECT_EQ(f.weak_rotor(), 0);
  in.tilt_rad = 0.04;  // below level_tilt_rad 0.05, but still turning
  in.pitch_rate_rad_s = 0.6;
  EXPECT_EQ(f.Update(in, kDtS), HoverFeasibility::Phase::kLevelling);
  in.pitch_rate_rad_s = -0.4;  // below level_rate_rad_s 0.5
  EXPECT_EQ(f.Update(in, kDtS), HoverFeasibility::Phase::kDescending);
  in.tilt_rad = 0.3;  // descending stays descending
  EXPECT_EQ(f.Update(in, kDtS), HoverFeasibility::Phase::kDescending);
}

TEST(HoverFeasibilityTest, SinkWithTheAllocationLimitedLatchesAtTheReportedFloor) {
  // An 80 % loss: FORCE's thrust_scale 0.15 is below the plausibility floor
  // and refused, so the efficiencies in use stay near 1; the vehicle sinks.
  const EfficiencyParams params;
  HoverFeasibility f(params, kMaxRotorForceN, kWeightN);
  FeasibilityInputs in;
  in.reported_scale[1] = 0.15;
  in.allocation_limited = true;
  in.altitude_lag_m = 0.2;  // > sink_detect_altitude_m 0.15
  in.sink_behind_m_s = 0.5;
  const double taken_s = RunUntilInfeasible(&f, in, 1.0);
  EXPECT_NEAR(taken_s, params.sink_detect_s, 1.5 * kDtS);
  EXPECT_EQ(f.cause(), HoverFeasibility::Cause::kSink);
  EXPECT_EQ(f.weak_rotor(), 1);
  EXPECT_DOUBLE_EQ(f.weak_efficiency(), 0.15);
  // Only a lower estimate is taken after a sink detection.
  in.following_force = true;
  in.efficiency[1] = 0.3;
  f.Update(in, kDtS);
  EXPECT_DOUBLE_EQ(f.weak_efficiency(), 0.15);
}

TEST(HoverFeasibilityTest, SinkWithoutAReportPicksTheHarderDrivenRotorAtTheBound) {
  HoverFeasibility f(EfficiencyParams(), kMaxRotorForceN, kWeightN);
  FeasibilityInputs in;
  in.allocation_limited = true;
  in.altitude_lag_m = 0.3;
  in.sink_behind_m_s = 1.0;
  in.command_rad_s[0] = 1200.0;
  in.command_rad_s[1] = 650.0;
  RunUntilInfeasible(&f, in, 1.0);
  EXPECT_EQ(f.weak_rotor(), 0);
  EXPECT_NEAR(f.weak_efficiency(), 0.3457, 1e-4);
}

TEST(HoverFeasibilityTest, NoSinkDetectionWhileClimbingCloseToTheReference) {
  HoverFeasibility f(EfficiencyParams(), kMaxRotorForceN, kWeightN);
  FeasibilityInputs in;
  in.allocation_limited = true;
  in.altitude_lag_m = 0.1;  // within sink_detect_altitude_m
  in.sink_behind_m_s = 1.0;
  RunUntilInfeasible(&f, in, 2.0);
  EXPECT_FALSE(f.infeasible());
  in.altitude_lag_m = 0.5;  // far below, but catching up
  in.sink_behind_m_s = -0.2;
  RunUntilInfeasible(&f, in, 2.0);
  EXPECT_FALSE(f.infeasible());
}

}  // namespace
}  // namespace birotor
