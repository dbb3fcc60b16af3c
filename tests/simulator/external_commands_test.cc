// The simulator as the vehicle's ESCs (Simulator::UseExternalCommands): a
// command reaches the motors at the step it arrives and is held; without
// commands for the timeout the motors spool down with tau_m and the
// simulator says so; one commander at a time, stamps checked, bad speeds
// refused (issue 23 item 4).
#include <gtest/gtest.h>

#include <cmath>

#include "simulator/scenario_yaml.h"
#include "simulator/simulator.h"
#include "tests/simulator/test_support.h"

namespace birotor {
namespace {

TEST(ExternalCommandsTest, HeldThenSpooledDownAfterTheTimeout) {
  Scenario scenario = LoadScenario(ScenarioPath("hover"));
  scenario.duration_s = 1.0;
  Simulator sim(scenario);
  sim.UseExternalCommands(0.1);
  const double command[2] = {700.0, 710.0};
  EXPECT_EQ(sim.OfferMotorCommand(0, sim.utime(), command), EscVerdict::kAccepted);
  while (sim.time_s() < 0.05) sim.Step(nullptr);
  EXPECT_EQ(sim.input().omega_cmd_rad_s[0], 700.0);
  EXPECT_EQ(sim.input().omega_cmd_rad_s[1], 710.0);
  EXPECT_FALSE(sim.command_timed_out());
  // Last command at 0; past 0.1 s the ESCs command 0.
  while (sim.time_s() < 0.3) sim.Step(nullptr);
  EXPECT_TRUE(sim.command_timed_out());
  EXPECT_EQ(sim.command_timeouts(), 1);
  EXPECT_EQ(sim.input().omega_cmd_rad_s[0], 0.0);
  // First-order spool-down from ~700 rad/s for ~0.2 s with tau_m = 35 ms.
  EXPECT_LT(sim.state()(kPlantOmega1), 700.0 * std::exp(-0.19 / 0.035));
  // A new command ends the timeout at once (the old stream went silent: a
  // new seq stream may take over).
  EXPECT_EQ(sim.OfferMotorCommand(500, sim.utime(), command), EscVerdict::kAccepted);
  sim.Step(nullptr);
  EXPECT_FALSE(sim.command_timed_out());
  EXPECT_EQ(sim.input().omega_cmd_rad_s[1], 710.0);
}

TEST(ExternalCommandsTest, BadCommandsAreRefusedAndTheLastGoodOneHeld) {
  Simulator sim(LoadScenario(ScenarioPath("hover")));
  sim.UseExternalCommands(0.1);
  while (sim.time_s() < 0.5) sim.Step(nullptr);
  const int64_t now = sim.utime();
  const double good[2] = {690.0, 700.0};
  ASSERT_EQ(sim.OfferMotorCommand(10, now, good), EscVerdict::kAccepted);
  const double nan[2] = {std::nan(""), 650.0}, high[2] = {1200.5, 650.0}, negative[2] = {-1.0, 650.0};
  EXPECT_EQ(sim.OfferMotorCommand(11, now + 1, nan), EscVerdict::kOutOfRange);
  EXPECT_EQ(sim.OfferMotorCommand(11, now + 1, high), EscVerdict::kOutOfRange);  // omega_max 1200
  EXPECT_EQ(sim.OfferMotorCommand(11, now + 1, negative), EscVerdict::kOutOfRange);
  // Stamps: 0 (older than the 0.1 s timeout), a repeat, +1000 s.
  EXPECT_EQ(sim.OfferMotorCommand(11, 0, good), EscVerdict::kStale);
  EXPECT_EQ(sim.OfferMotorCommand(11, now, good), EscVerdict::kStale);
  EXPECT_EQ(sim.OfferMotorCommand(11, now + 1000000000, good), EscVerdict::kFuture);
  // A second commander (seq far from the locked stream) is ignored.
  const double flip[2] = {0.0, 1200.0};
  EXPECT_EQ(sim.OfferMotorCommand(900000, now + 2, flip), EscVerdict::kForeign);
  sim.Step(nullptr);
  EXPECT_EQ(sim.input().omega_cmd_rad_s[0], 690.0);
  EXPECT_EQ(sim.input().omega_cmd_rad_s[1], 700.0);
  const EscCounters& n = sim.esc_counters();
  EXPECT_EQ(n.received, 8);
  EXPECT_EQ(n.accepted, 1);
  EXPECT_EQ(n.out_of_range, 3);
  EXPECT_EQ(n.stale, 2);
  EXPECT_EQ(n.future, 1);
  EXPECT_EQ(n.foreign, 1);
  // Nothing good for the timeout: the ESCs spool down.
  while (sim.time_s() < 0.65) sim.Step(nullptr);
  EXPECT_TRUE(sim.command_timed_out());
  EXPECT_EQ(sim.input().omega_cmd_rad_s[0], 0.0);
}

}  // namespace
}  // namespace birotor
