// The supervised controller when flight degrades (issue 34,
// controller/vehicle_controller.h): a hover-infeasible descent stays latched
// and keeps its flare when FORCE loses VALID, an 80 % loss whose FORCE sits
// below the plausibility floor is found from the sink, every descent slews
// its rotor commands, and a consistent run of POSEs far from a drifted
// observer is re-acquired.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "controller/vehicle_controller.h"
#include "tests/controller/hover_feed.h"

namespace birotor {
namespace {

// Largest change of either rotor command between two periods [rad/s].
double MaxCommandStep(HoverFeed* feed, int periods) {
  MotorCommand last = feed->Period();
  double step = 0.0;
  for (int k = 0; k < periods; ++k) {
    const MotorCommand c = feed->Period();
    for (int i = 0; i < 2; ++i) step = std::max(step, std::fabs(c.omega_cmd_rad_s[i] - last.omega_cmd_rad_s[i]));
    last = c;
  }
  return step;
}

TEST(DegradedFlightTest, InfeasibleDescentStaysLatchedAndFlaresWhenForceLosesValid) {
  const ControllerConfig config;
  HoverFeed feed(config);
  feed.Settle();
  feed.climb_m_s = 0.5;
  feed.Run(500);  // z = 0.5 m
  feed.climb_m_s = 0.0;
  feed.scale2 = 0.3;
  MotorCommand c = feed.Run(150);
  ASSERT_TRUE(c.status & kCommandHoverInfeasible);
  const double latched = feed.controller().health().efficiency[1];
  EXPECT_NEAR(latched, 0.3, 0.01);
  // The estimator raises MODEL_MISMATCH: VALID withdrawn, the conditioned
  // efficiency decays towards 1 (decay_s 3 s: above the 0.346 bound after
  // 0.2 s). 1 s later the descent and the weak rotor's efficiency stand.
  feed.force_status = 0;
  c = feed.Run(500);
  EXPECT_TRUE(c.status & kCommandFallbackActive);
  EXPECT_TRUE(c.status & kCommandHoverInfeasible);
  EXPECT_TRUE(c.status & kCommandDescending);
  EXPECT_DOUBLE_EQ(feed.controller().health().efficiency[1], latched);
  EXPECT_EQ(feed.controller().health().infeasible, 1);
  // ... and the flare still comes near the ground, rotor 2 at omega_max.
  feed.climb_m_s = -1.0;
  while (feed.z_m() > 0.05) c = feed.Period();
  EXPECT_TRUE(feed.controller().health().flaring);
  EXPECT_EQ(feed.controller().health().flares, 1);
  EXPECT_NEAR(c.omega_cmd_rad_s[1], config.vehicle.omega_max_rad_s, 1e-9);
}

TEST(DegradedFlightTest, LossAtThePlausibilityFloorIsFoundFromTheSink) {
  // Rotor 2 at 15 %: FORCE's thrust_scale is below min_plausible_thrust_scale
  // (0.2) and refused, force feedback falls back (e towards 1). The vehicle
  // sinks at 3 m/s: the law asks for more than both rotors can make.
  const ControllerConfig config;
  HoverFeed feed(config);
  feed.Settle();
  feed.scale2 = 0.15;
  feed.climb_m_s = -3.0;
  MotorCommand c;
  int periods = 0;
  for (; periods < 250 && !(c.status & kCommandHoverInfeasible); ++periods) c = feed.Period();
  const ControllerHealth& health = feed.controller().health();
  EXPECT_EQ(health.infeasible_by_sink, 1);
  EXPECT_TRUE(c.status & kCommandDescending);
  // Measured: found 0.350 s after the loss (0.15 m below the reference after
  // 50 ms, the allocation limited once the law asks for more than 2 x 66 N,
  // then sink_detect_s 0.1 s).
  EXPECT_GE(periods * kPeriodUs * 1e-6, config.efficiency.sink_detect_s);
  EXPECT_LE(periods * kPeriodUs * 1e-6, 0.35 * 1.5);
  // Rotor 2 is flown with FORCE's refused report, low-passed over
  // infeasible_s: 0.15 + 0.85 exp(-0.35 / 0.1) = 0.176 (measured 0.1752);
  // rotor 1 with the fallback's e = 1.
  EXPECT_NEAR(health.efficiency[1], 0.176, 0.01);
  EXPECT_DOUBLE_EQ(health.efficiency[0], 1.0);
}

TEST(DegradedFlightTest, AFlaggedScaleBelowTheFloorIsFlownAsTheFloor) {
  // Rotor 2 at 15 %, FORCE VALID and flagging rotor 2's fault: the scale is
  // at most the floor (0.2) and flown as 0.2 after at_floor_samples (5) in a
  // row; hover is infeasible from the efficiency (0.2 < 0.346) after
  // infeasible_s, no sink needed.
  const ControllerConfig config;
  HoverFeed feed(config);
  feed.Settle();
  feed.force_status = kStatusValid | kStatusRotor2Fault;
  feed.scale2 = 0.15;
  feed.Run(2);  // 4 samples: still refused
  const ControllerHealth& health = feed.controller().health();
  EXPECT_EQ(health.force_at_floor, 0);
  EXPECT_EQ(health.force.rejected_invalid, 4);
  const MotorCommand c = feed.Run(100);  // 0.2 s
  // 204 samples, the first at_floor_samples - 1 refused, every later one flown at the floor.
  EXPECT_EQ(health.force_at_floor, 204 - (config.supervision.at_floor_samples - 1));
  EXPECT_EQ(health.force.rejected_invalid, config.supervision.at_floor_samples - 1);
  EXPECT_TRUE(c.status & kCommandHoverInfeasible);
  EXPECT_EQ(health.infeasible_by_sink, 0);
  EXPECT_NEAR(health.efficiency[1], 0.2, 0.005);
}

TEST(DegradedFlightTest, AScaleBelowTheFloorWithoutTheFaultFlagIsRefused) {
  const ControllerConfig config;
  HoverFeed feed(config);
  feed.Settle();
  feed.scale2 = 0.15;  // VALID only: an implausible scale (issue 23's attack), refused
  feed.Run(50);
  EXPECT_EQ(feed.controller().health().force_at_floor, 0);
  EXPECT_EQ(feed.controller().health().force.rejected_invalid, 100);
}

TEST(DegradedFlightTest, EveryDescentSlewsItsCommands) {
  const ControllerConfig config;
  const double max_step_rad_s = config.supervision.degraded_omega_rate_rad_s2 * kPeriodUs * 1e-6;  // 40 rad/s
  {
    HoverFeed feed(config);
    feed.Settle();
    feed.send_pose = false;  // POSE lost: descent on the IMU
    feed.Run(26);            // 52 ms > pose_timeout_s
    EXPECT_LE(MaxCommandStep(&feed, 500), max_step_rad_s + 1e-9);
    EXPECT_EQ(feed.controller().health().descents, 1);
  }
  {
    HoverFeed feed(config);
    feed.Settle();
    feed.scale2 = 0.3;  // hover infeasible after infeasible_s: level, then descend
    MotorCommand c;
    while (!(c.status & kCommandHoverInfeasible)) c = feed.Period();
    EXPECT_LE(MaxCommandStep(&feed, 500), max_step_rad_s + 1e-9);
  }
}

TEST(DegradedFlightTest, ConsistentPosesFarFromADriftedObserverAreReacquired) {
  const ControllerConfig config;
  HoverFeed feed(config);
  feed.Settle();
  feed.Teleport(1.0);  // 1 m above where the observer has it: outside the 0.3 m gate
  feed.Run(5 * (config.supervision.pose_reacquire_count - 1));  // 100 Hz POSE: 4 refused
  const ControllerHealth& health = feed.controller().health();
  EXPECT_EQ(health.pose.rejected_gate, config.supervision.pose_reacquire_count - 1);
  EXPECT_EQ(health.pose_reacquisitions, 0);
  feed.Run(5);  // the 5th in a row
  EXPECT_EQ(health.pose_reacquisitions, 1);
  EXPECT_EQ(health.pose_gate_resets, 0);
  EXPECT_NEAR(feed.controller().state().position_m.y(), 1.0, 0.01);
  feed.Run(50);
  EXPECT_EQ(health.pose.rejected_gate, config.supervision.pose_reacquire_count - 1);
}

}  // namespace
}  // namespace birotor
