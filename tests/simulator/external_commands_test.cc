// The simulator as the vehicle's ESCs (Simulator::UseExternalCommands): a
// command reaches the motors at the step it arrives and is held; without
// commands for the timeout the motors spool down with tau_m and the
// simulator says so.
#include <gtest/gtest.h>

#include <cmath>

#include "params/scenario_yaml.h"
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
  sim.SetMotorCommand(command, sim.utime());
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
  // A new command ends the timeout at once.
  sim.SetMotorCommand(command, sim.utime());
  sim.Step(nullptr);
  EXPECT_FALSE(sim.command_timed_out());
  EXPECT_EQ(sim.input().omega_cmd_rad_s[1], 710.0);
}

TEST(ExternalCommandsTest, NonFiniteCommandIsTakenAsZero) {
  Simulator sim(LoadScenario(ScenarioPath("hover")));
  sim.UseExternalCommands(0.1);
  const double command[2] = {std::nan(""), 650.0};
  sim.SetMotorCommand(command, 0);
  sim.Step(nullptr);
  EXPECT_EQ(sim.input().omega_cmd_rad_s[0], 0.0);
  EXPECT_EQ(sim.input().omega_cmd_rad_s[1], 650.0);
}

}  // namespace
}  // namespace birotor
