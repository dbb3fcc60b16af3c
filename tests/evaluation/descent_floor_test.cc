// The level descent's floor (evaluation/descent_floor.h) on the reference
// vehicle: m = 4 + 2 x 0.28812 = 4.57624 kg, c_T omega_max^2 = 66.24 N, so a
// 70 % loss sinks at >= 9.81 - 2 x 0.3 x 66.24 / 4.57624 = 1.125 m/s^2 and an
// 80 % one at >= 4.020 m/s^2.
#include "evaluation/descent_floor.h"

#include <gtest/gtest.h>

#include <cmath>

#include "samples/motor_command.h"

namespace birotor {
namespace {

Scenario WithLoss(double scale) {
  Scenario scenario;
  scenario.faults.thrust_steps = {ThrustStep{1.0, 2, 0.9}, ThrustStep{2.0, 2, scale}};
  return scenario;
}

TEST(DescentFloorTest, SinkAccelerationOfTheWeakRotorsLevelMaximum) {
  EXPECT_NEAR(WeakestFinalThrustScale(WithLoss(0.3)), 0.3, 1e-12);
  EXPECT_NEAR(LevelSinkAccelM_S2(WithLoss(0.3)), 1.125, 1e-3);
  EXPECT_NEAR(LevelSinkAccelM_S2(WithLoss(0.2)), 4.020, 1e-3);
}

TEST(DescentFloorTest, FromTheTruthAtTheFirstDescendingCommandAfterTheFault) {
  const Scenario scenario = WithLoss(0.3);
  ClosedLoopRun run;
  run.has_ground = true;
  run.ground_z_m = 0.0;
  run.fault_utime = 1000;
  for (int k = 0; k < 5; ++k) {
    MotorCommand command;
    command.utime = 1000 * k;
    command.status = k == 0 || k >= 3 ? kCommandDescending : 0;  // k = 0: before the fault
    run.commands.push_back(command);
    TrackedSample sample;
    sample.truth.utime = 1000 * k;
    sample.truth.z_m = 1.0 - 0.1 * k;
    sample.truth.z_dot_m_s = 0.5;  // still climbing: the climb counts as height
    run.samples.push_back(sample);
  }
  const DescentFloor floor = LevelDescentFloor(run, scenario);
  ASSERT_TRUE(floor.found);
  EXPECT_NEAR(floor.start_s, 0.003, 1e-12);
  EXPECT_NEAR(floor.height_m, 0.7, 1e-12);
  // sqrt(0.5^2 + 2 x 1.125 x 0.7) = 1.351 m/s
  EXPECT_NEAR(floor.touchdown_m_s, std::sqrt(0.25 + 2.0 * LevelSinkAccelM_S2(scenario) * 0.7), 1e-12);
  EXPECT_NEAR(floor.touchdown_m_s, 1.351, 1e-3);
  run.has_ground = false;
  EXPECT_FALSE(LevelDescentFloor(run, scenario).found);
}

}  // namespace
}  // namespace birotor
