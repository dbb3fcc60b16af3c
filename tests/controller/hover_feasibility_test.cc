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

// Runs periods of in, its climb rate changing at climb_accel [m/s^2], until
// the phase is not kFeasible or seconds have passed; returns the time taken [s].
double RunUntilInfeasible(HoverFeasibility* f, FeasibilityInputs in, double seconds, double climb_accel_m_s2 = 0.0) {
  double t = 0.0;
  while (t < seconds && !f->infeasible()) {
    f->Update(in, kDtS);
    in.climb_rate_m_s += climb_accel_m_s2 * kDtS;
    t += kDtS;
  }
  return t;
}

// A loss the rotors cannot hold: the sink grows at this rate [m/s^2].
constexpr double kSinkGrowsM_s2 = -1.0;

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
  const double taken_s = RunUntilInfeasible(&f, in, 1.0, kSinkGrowsM_s2);
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
  RunUntilInfeasible(&f, in, 1.0, kSinkGrowsM_s2);
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
  RunUntilInfeasible(&f, in, 2.0, kSinkGrowsM_s2);
  EXPECT_FALSE(f.infeasible());
}

TEST(HoverFeasibilityTest, NoSinkDetectionWhileTheSinkShrinks) {
  // Far below and behind with the allocation limited, but the limited
  // rotors slow the sink: they hold the weight (payload +15 %, 60 % loss,
  // 0.6 s after it: the nominal map's 1.40 m fall, where a latch cost 1.70 m).
  const EfficiencyParams params;
  HoverFeasibility f(params, kMaxRotorForceN, kWeightN);
  FeasibilityInputs in;
  in.allocation_limited = true;
  in.altitude_lag_m = 0.5;
  in.sink_behind_m_s = 0.9;
  in.climb_rate_m_s = -0.9;
  EXPECT_GE(RunUntilInfeasible(&f, in, 2.0, 0.3), 2.0);
  EXPECT_FALSE(f.infeasible());
  // Steady where it got to is not growing either; growing is detected
  // within two windows.
  in.climb_rate_m_s = -0.9 + 0.3 * 2.0;
  EXPECT_GE(RunUntilInfeasible(&f, in, 1.0), 1.0);
  EXPECT_LE(RunUntilInfeasible(&f, in, 1.0, kSinkGrowsM_s2), 2.0 * params.sink_detect_s + 1.5 * kDtS);
  EXPECT_TRUE(f.infeasible());
}

// Latched from the sink with rotor 1 weak (the 80 % loss above), then the
// level and calm descent with rotor 1 commanded at command_1 and rotor 0 at
// 750 rad/s, from the climb rate climb [m/s] changing at accel [m/s^2], for
// seconds; the height follows the climb rate unless held (on the ground).
// Returns the feasibility.
HoverFeasibility DescendAfterASink(double command_1, double accel_m_s2, double climb_m_s, double seconds,
                                   bool height_held = false) {
  HoverFeasibility f(EfficiencyParams(), kMaxRotorForceN, kWeightN);
  f.MeasureRecovery(1200.0, 9.81);
  FeasibilityInputs in;
  in.reported_scale[1] = 0.3;
  in.allocation_limited = true;
  in.altitude_lag_m = 0.5;
  in.sink_behind_m_s = 0.5;
  RunUntilInfeasible(&f, in, 1.0, kSinkGrowsM_s2);
  in.command_rad_s[0] = 750.0;
  in.command_rad_s[1] = command_1;
  in.climb_rate_m_s = climb_m_s;
  for (double t = 0.0; t < seconds; t += kDtS) {
    f.Update(in, kDtS);
    if (!height_held) in.altitude_m += in.climb_rate_m_s * kDtS;
    in.climb_rate_m_s += accel_m_s2 * kDtS;
  }
  return f;
}

// Two recovery windows and a period to spare [s].
double TwoWindowsS() { return 2.0 * EfficiencyParams().sink_recover_s + 0.01; }

TEST(HoverFeasibilityTest, SinkLatchIsUndoneWhenTheCommandsHoldTheWeightWithTheMargin) {
  // A 60 % loss with a +15 % payload: the weak rotor holds its share of the
  // weight at (1172 / 1200)^2 = 0.954 of its maximum in a steady descent,
  // a margin of 1.048 >= 1.02.
  const HoverFeasibility f = DescendAfterASink(1172.0, 0.0, -0.4, TwoWindowsS());
  EXPECT_FALSE(f.infeasible());
  EXPECT_EQ(f.recoveries(), 1);
  EXPECT_EQ(f.entries_by_sink(), 1);
  // The weak rotor keeps its latched efficiency until FORCE is usable.
  EXPECT_DOUBLE_EQ(f.EfficiencyFor(1, 0.95), 0.3);
  EXPECT_DOUBLE_EQ(f.EfficiencyFor(0, 1.0), 1.0);
}

TEST(HoverFeasibilityTest, SaturatedRotorThatStillSlowsTheSinkRecovers) {
  // At omega_max the rotors hold m (g + a): +0.5 m/s^2 is a margin of 1.051.
  EXPECT_FALSE(DescendAfterASink(1200.0, 0.5, -0.8, TwoWindowsS()).infeasible());
  // One window is not enough.
  EXPECT_TRUE(DescendAfterASink(1200.0, 0.5, -0.8, 0.5 * TwoWindowsS()).infeasible());
  // +0.1 m/s^2 is 1.010: not enough.
  EXPECT_TRUE(DescendAfterASink(1200.0, 0.1, -0.8, 1.0).infeasible());
}

TEST(HoverFeasibilityTest, SinkLatchHoldsWithoutTheMarginOnTheGroundOrWithoutTheMeasure) {
  // Steady at (1195 / 1200)^2 = 0.992: margin 1.008.
  EXPECT_TRUE(DescendAfterASink(1195.0, 0.0, -0.4, 2.0).infeasible());
  // On the ground nothing moves: the rotors do not carry the vehicle. After
  // the impact the observer's climb rate decays (here from -1.5 m/s at
  // 3 m/s^2, a margin of 1.31 by the rate) while the height stays.
  EXPECT_TRUE(DescendAfterASink(600.0, 0.0, 0.0, 2.0).infeasible());
  EXPECT_TRUE(DescendAfterASink(600.0, 3.0, -1.5, 0.45, true).infeasible());
  // Without MeasureRecovery the latch holds for the flight.
  HoverFeasibility f(EfficiencyParams(), kMaxRotorForceN, kWeightN);
  FeasibilityInputs in;
  in.allocation_limited = true;
  in.altitude_lag_m = 0.5;
  in.sink_behind_m_s = 0.5;
  RunUntilInfeasible(&f, in, 1.0, kSinkGrowsM_s2);
  in.command_rad_s[0] = in.command_rad_s[1] = 700.0;
  in.climb_rate_m_s = -0.4;
  for (int i = 0; i < 1000; ++i) f.Update(in, kDtS);
  EXPECT_TRUE(f.infeasible());
}

TEST(HoverFeasibilityTest, SinkDetectionRearmsOnceTheVehicleNoLongerFallsBehind) {
  const EfficiencyParams params;
  HoverFeasibility f = DescendAfterASink(1172.0, 0.0, -0.4, TwoWindowsS());
  ASSERT_FALSE(f.infeasible());
  // The climb back starts behind the reference with the weak rotor
  // saturated (its transient may grow the sink a moment): not a new sink.
  FeasibilityInputs in;
  in.allocation_limited = true;
  in.altitude_lag_m = 1.0;
  in.sink_behind_m_s = 0.4;
  EXPECT_GE(RunUntilInfeasible(&f, in, 1.0, kSinkGrowsM_s2), 1.0);
  EXPECT_FALSE(f.infeasible());
  // Caught up once; a growing sink after that is detected again.
  in.sink_behind_m_s = -0.1;
  f.Update(in, kDtS);
  in.sink_behind_m_s = 0.4;
  EXPECT_NEAR(RunUntilInfeasible(&f, in, 1.0, kSinkGrowsM_s2), params.sink_detect_s, 1.5 * kDtS);
  EXPECT_EQ(f.entries_by_sink(), 2);
}

}  // namespace
}  // namespace birotor
