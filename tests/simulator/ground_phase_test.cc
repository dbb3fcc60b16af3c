// Tests of the ground phase of the simulator (scenario.h GroundParams,
// shared/spec/gauges.md): rest with the motors stopped, spool-up, lift-off
// when the thrust exceeds the weight, landing and disarm.
#include <gtest/gtest.h>

#include <cmath>

#include "params/scenario_yaml.h"
#include "simulator/simulator.h"
#include "test_support.h"

namespace birotor {
namespace {

// m_p g L / k of the reference vehicle: 0.28812 * 9.81 * 0.25 / 2628 [rad].
constexpr double kRestDeflectionRad = 2.6887e-4;

TEST(GroundPhaseTest, RestsWithMotorsStoppedThenLiftsOffAndFlies) {
  Simulator sim(LoadScenario(ScenarioPath("gauge_offset"), {"scenario.duration_s=8"}));
  EXPECT_TRUE(sim.on_ground());
  CollectingSink sink;
  sim.Run(&sink);
  // At rest (first 3 s): body still at the start, arms bent by their tip
  // weight only (arm 1 up, arm 2 down in the frame of interface.md).
  for (size_t k = 100; k < 3000; k += 50) {
    const TruthSample& t = sink.truth[k];
    EXPECT_EQ(t.z_m, 0.0);
    EXPECT_EQ(t.phi_rad, 0.0);
    EXPECT_NEAR(t.deflection_rad[0], kRestDeflectionRad, 1e-8);
    EXPECT_NEAR(t.deflection_rad[1], -kRestDeflectionRad, 1e-8);
    EXPECT_EQ(t.force_n[0], 0.0);
  }
  // MOTOR: 0 rad/s commands, telemetry near 0 (never negative, noise 5 rad/s).
  for (size_t k = 0; k < 1500; ++k) {
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(sink.motor[k].omega_cmd_rad_s[i], 0.0);
      EXPECT_GE(sink.motor[k].omega_meas_rad_s[i], 0.0);
      EXPECT_LT(sink.motor[k].omega_meas_rad_s[i], 25.0);
    }
  }
  // IMU at rest reads gravity only.
  EXPECT_NEAR(sink.imu[1000].accel_z_m_s2, 9.81, 0.25);
  // Spool-up ramp to idle: half of 300 rad/s half-way (3.5 s).
  EXPECT_NEAR(sink.motor[1750].omega_cmd_rad_s[0], 150.0, 1.0);
  // Lift-off only after the controller takes over at 4 s, within 1.5 s.
  ASSERT_GT(sim.liftoff_utime(), 4'000'000);
  EXPECT_LT(sim.liftoff_utime(), 5'500'000);
  // Then it flies the gentle trajectory upwards.
  EXPECT_GT(sink.truth.back().z_m, 0.1);
  EXPECT_FALSE(sim.on_ground());
}

TEST(GroundPhaseTest, LandingEndsOnTheGroundWithMotorsStopped) {
  Simulator sim(LoadScenario(ScenarioPath("gauge_offset"),
                             {"scenario.duration_s=16",
                              "trajectory.waypoints=[{start_s: 0, duration_s: 4, x_m: 0.2, "
                              "z_m: 0.4}]",
                              "ground.land=true", "ground.landing_duration_s=4", "ground.rest_after_s=2"}));
  CollectingSink sink;
  sim.Run(&sink);
  EXPECT_TRUE(sim.on_ground());
  const TruthSample& last = sink.truth.back();
  EXPECT_EQ(last.z_m, 0.0);
  EXPECT_NEAR(last.x_m, 0.2, 0.05);
  EXPECT_EQ(sink.motor.back().omega_cmd_rad_s[0], 0.0);
  EXPECT_NEAR(last.deflection_rad[0], kRestDeflectionRad, 2e-6);  // motors spun down for 2 s
}

TEST(GroundPhaseTest, KeysAreValidated) {
  EXPECT_THROW(LoadScenario(ScenarioPath("gauge_offset"), {"ground.rest_s=30"}), ParamError);
  EXPECT_THROW(LoadScenario(ScenarioPath("bench"), {"ground.enabled=true"}), ParamError);
  EXPECT_THROW(LoadScenario(ScenarioPath("gauge_offset"), {"ground.land=true", "ground.landing_duration_s=14"}),
               ParamError);
}

TEST(GroundPhaseTest, EveryGaugeScenarioLoads) {
  for (const char* name : {"gauge_offset", "gauge_drift", "gauge_vibration", "gauge_airborne", "bench_gauge"}) {
    EXPECT_NO_THROW(LoadScenario(ScenarioPath(name), {})) << name;
  }
}

}  // namespace
}  // namespace birotor
