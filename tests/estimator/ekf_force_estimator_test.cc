// The EKF on short simulated runs: accuracy at hover and while manoeuvring,
// rotor-fault detection after a thrust loss, the innovation gate. Bounds are
// loose enough never to flake (measured values are about half of them).
#include "estimator/ekf_force_estimator.h"

#include <gtest/gtest.h>

#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace {

using testing_support::ForceMae;
using testing_support::ReferenceConfig;
using testing_support::RunScenario;
using testing_support::ScenarioFile;
using testing_support::ScenarioRun;

TEST(EkfForceEstimatorTest, TracksTheForcesAtHover) {
  const ScenarioRun run =
      RunScenario(LoadScenario(ScenarioFile("hover"), {"scenario.duration_s=3"}), ReferenceConfig("ekf"));
  ASSERT_GT(run.pairs.size(), 2900u);
  EXPECT_EQ(run.non_finite, 0);
  EXPECT_LT(ForceMae(run, 0, 500000), 0.12);  // measured ~0.07 N
  EXPECT_LT(ForceMae(run, 1, 500000), 0.12);
  for (const auto& p : run.pairs) {
    EXPECT_EQ(p.status & (kStatusRotor1Fault | kStatusRotor2Fault), 0);
    if (p.utime > 500000) {
      EXPECT_TRUE(p.status & kStatusValid);
    }
  }
}

TEST(EkfForceEstimatorTest, TracksTheForcesDuringAManoeuvre) {
  // The aggressive quintic (1 m in 2 s), cut to its move.
  const ScenarioRun run =
      RunScenario(LoadScenario(ScenarioFile("aggressive"), {"scenario.duration_s=3"}), ReferenceConfig("ekf"));
  EXPECT_LT(ForceMae(run, 0, 500000), 0.12);
  EXPECT_LT(ForceMae(run, 1, 500000), 0.12);
}

TEST(EkfForceEstimatorTest, FlagsTheRotorThatLostThrust) {
  const ScenarioRun run =
      RunScenario(LoadScenario(ScenarioFile("thrust_loss"),
                               {"scenario.duration_s=2", "faults.thrust_steps=[{time_s: 1.0, rotor: 2, scale: 0.75}]"}),
                  ReferenceConfig("ekf"));
  int64_t first_flag = -1;
  for (const auto& p : run.pairs) {
    EXPECT_EQ(p.status & kStatusRotor1Fault, 0);
    if ((p.status & kStatusRotor2Fault) && first_flag < 0) first_flag = p.utime;
    if (p.utime == 1100000) {
      EXPECT_NEAR(p.thrust_scale[1], p.true_thrust_scale[1], 0.04);
    }
    if (p.utime > 1200000) {
      EXPECT_TRUE(p.status & kStatusRotor2Fault);
    }
  }
  ASSERT_GE(first_flag, 1000000);          // never before the step
  EXPECT_LE(first_flag, 1000000 + 80000);  // measured ~35 ms
}

TEST(EkfForceEstimatorTest, DoesNotFlagThinAir) {
  const ScenarioRun run = RunScenario(
      LoadScenario(ScenarioFile("hover"), {"scenario.duration_s=3", "faults.initial_thrust_scale=[0.9, 0.9]"}),
      ReferenceConfig("ekf"));
  for (const auto& p : run.pairs) EXPECT_EQ(p.status & (kStatusRotor1Fault | kStatusRotor2Fault), 0);
  EXPECT_NEAR(run.pairs.back().thrust_scale[0], 0.9, 0.05);
  EXPECT_NEAR(run.pairs.back().thrust_scale[1], 0.9, 0.05);
}

TEST(EkfForceEstimatorTest, GateRejectsASpikeAndCountsIt) {
  const auto events =
      testing_support::RecordScenario("hover", {"scenario.duration_s=1.5", "sensors.pose.enabled=false"});
  EstimatorPipeline pipeline(ReferenceConfig("ekf"));
  ForceEstimate before, spiked, after;
  int strain_count = 0;
  for (const auto& e : events) {
    if (e.kind == testing_support::InputEvent::kMotor) pipeline.OnMotor(e.motor);
    if (e.kind == testing_support::InputEvent::kImu) pipeline.OnImu(e.imu);
    if (e.kind != testing_support::InputEvent::kStrain) continue;
    ++strain_count;
    StrainSample s = e.strain;
    if (strain_count == 1000) {
      s.deflection_rad[0] += 50 * 2e-5;  // 50 sigma
      ASSERT_TRUE(pipeline.OnStrain(s, &spiked));
    } else {
      ASSERT_TRUE(pipeline.OnStrain(s, strain_count == 999 ? &before : &after));
    }
  }
  EXPECT_TRUE(spiked.status & kStatusMeasurementRejected);
  EXPECT_TRUE(spiked.status & kStatusValid);
  EXPECT_NEAR(spiked.force_n[0], before.force_n[0], 0.05);
  EXPECT_EQ(pipeline.health().inputs[static_cast<int>(InputChannel::kStrain)].rejected_gate, 1);
  EXPECT_FALSE(after.status & kStatusMeasurementRejected);
  EXPECT_GT(pipeline.health().nis_max, 1000.0);
}

TEST(EkfForceEstimatorTest, SensorFaultsStayFiniteAndCounted) {
  const ScenarioRun run = RunScenario(
      LoadScenario(ScenarioFile("sensor_faults"),
                   {"scenario.duration_s=11", "faults.motor_telemetry_gap={start_s: 9.0, duration_s: 1.0}"}),
      ReferenceConfig("ekf"));
  EXPECT_EQ(run.non_finite, 0);
  const InputCounters& strain = run.health.inputs[static_cast<int>(InputChannel::kStrain)];
  EXPECT_EQ(strain.rejected_invalid, 1);  // the NaN sample
  EXPECT_EQ(strain.out_of_order, 1);      // the one delivered late
  EXPECT_GE(strain.gaps, 1);              // the 150 ms gap
  EXPECT_GE(strain.missing_samples, 150);
  EXPECT_GT(strain.rejected_gate, 20);                                                          // ~0.5 % spikes
  EXPECT_GE(run.health.resets, 2);                                                              // start + the gap
  EXPECT_EQ(run.health.inputs[static_cast<int>(InputChannel::kMotor)].telemetry_missing, 500);  // 1 s at 500 Hz
  std::vector<int64_t> fault_times;
  for (const FaultEvent& f : run.faults) fault_times.push_back(f.utime);
  EXPECT_LT(ForceMae(run, 0, 500000, fault_times, 0.2), 0.15);
  EXPECT_LT(ForceMae(run, 1, 500000, fault_times, 0.2), 0.15);
}

}  // namespace
}  // namespace birotor
