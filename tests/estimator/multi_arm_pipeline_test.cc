// The N-arm estimator's input path (estimator/multi_arm_pipeline.h) on the
// trirotor's simulated samples: one estimate per accepted strain sample,
// VALID once converged and never NaN; every bad sample counted where the
// birotor's pipeline counts it (a wrong count, a non-finite reading, a
// duplicate, an out-of-order stamp); a strain gap and a backwards jump reset
// the filter and say so (FILTER_RESET); a stale MOTOR withdraws VALID; every
// fusion report is counted on its input (fused, gated, NIS, the gate), the
// accelerometer's on its own, as the birotor's pipeline counts them.
#include "estimator/multi_arm_pipeline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "simulator/multi_arm_simulator.h"

namespace birotor {
namespace {

std::string SourceFile(const std::string& relative) { return std::string(BIROTOR_SOURCE_DIR) + "/" + relative; }

EstimatorConfig TrirotorConfig() {
  EstimatorConfig config = LoadEstimatorConfig(SourceFile("config/estimator.yaml"));
  config.vehicle = LoadVehicleDescription(SourceFile("config/vehicles/trirotor.yaml"));
  return config;
}

// The samples of 2 s of the trirotor's hover, in the order the simulator emits them.
struct Recorded : SampleSink {
  struct Event {
    int kind = 0;  // 0 strain, 1 motor, 2 imu
    MultiArmStrainSample strain;
    MultiArmMotorSample motor;
    ImuSample imu;
  };
  std::vector<Event> events;
  void OnStrainN(const MultiArmStrainSample& s) override { events.push_back({0, s, {}, {}}); }
  void OnMotorN(const MultiArmMotorSample& s) override { events.push_back({1, {}, s, {}}); }
  void OnImu(const ImuSample& s) override { events.push_back({2, {}, {}, s}); }
};

Recorded Hover(const EstimatorConfig& config) {
  const Scenario scenario =
      LoadScenario(SourceFile("config/scenarios/hover.yaml"), {"scenario.duration_s=2"}, config.vehicle.arm_count);
  MultiArmSimulator simulator(config.vehicle, scenario);
  Recorded recorded;
  simulator.Run(&recorded);
  return recorded;
}

// Feeds events [begin, end); returns the estimates published.
std::vector<MultiArmForceEstimate> Feed(const Recorded& r, size_t begin, size_t end, MultiArmPipeline* pipeline) {
  std::vector<MultiArmForceEstimate> out;
  for (size_t k = begin; k < end && k < r.events.size(); ++k) {
    const Recorded::Event& e = r.events[k];
    MultiArmForceEstimate estimate;
    if (e.kind == 1) pipeline->OnMotor(e.motor);
    if (e.kind == 2) pipeline->OnImu(e.imu);
    if (e.kind == 0 && pipeline->OnStrain(e.strain, &estimate)) out.push_back(estimate);
  }
  return out;
}

const InputCounters& Strain(const MultiArmPipeline& p) {
  return p.health().inputs[static_cast<int>(InputChannel::kStrain)];
}

TEST(MultiArmPipelineTest, OneFiniteEstimatePerStrainSampleValidOnceConverged) {
  const EstimatorConfig config = TrirotorConfig();
  const Recorded r = Hover(config);
  MultiArmPipeline pipeline(config);
  const std::vector<MultiArmForceEstimate> estimates = Feed(r, 0, r.events.size(), &pipeline);
  ASSERT_EQ(estimates.size(), 2000u);      // 2 s at 1 kHz
  EXPECT_EQ(pipeline.health().resets, 1);  // the start
  EXPECT_NE(estimates.front().status & kStatusFilterReset, 0);
  for (const MultiArmForceEstimate& e : estimates) {
    ASSERT_EQ(e.n_rotors, 3);
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(std::isfinite(e.force_n[static_cast<size_t>(i)]));
  }
  EXPECT_NE(estimates.back().status & kStatusValid, 0);
  EXPECT_EQ(estimates.back().rotor_fault_bits, 0);
  // Hover (config/vehicles/trirotor.yaml): 27.47 N on rotor 1, 14.32 N on rotors 2 and 3.
  EXPECT_NEAR(estimates.back().force_n[0], 27.47, 0.5);
  EXPECT_NEAR(estimates.back().force_n[1], 14.32, 0.5);
}

TEST(MultiArmPipelineTest, BadSamplesAreCountedNotFused) {
  const EstimatorConfig config = TrirotorConfig();
  const Recorded r = Hover(config);
  MultiArmPipeline pipeline(config);
  Feed(r, 0, r.events.size() / 2, &pipeline);
  MultiArmStrainSample last;
  for (const Recorded::Event& e : r.events) {
    if (e.kind == 0 && e.strain.utime <= pipeline.health().newest_utime) last = e.strain;
  }
  const int64_t invalid_before = Strain(pipeline).rejected_invalid;
  MultiArmForceEstimate estimate;
  MultiArmStrainSample wrong_count = last;
  wrong_count.utime += 1000;
  wrong_count.n_arms = 2;
  EXPECT_FALSE(pipeline.OnStrain(wrong_count, &estimate));
  MultiArmStrainSample infinite = last;
  infinite.utime += 1000;
  infinite.deflection_rad[1] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(pipeline.OnStrain(infinite, &estimate));
  EXPECT_EQ(Strain(pipeline).rejected_invalid, invalid_before + 2);
  EXPECT_FALSE(pipeline.OnStrain(last, &estimate));  // the newest again
  EXPECT_EQ(Strain(pipeline).duplicates, 1);
  MultiArmStrainSample older = last;
  older.utime -= 5000;
  EXPECT_FALSE(pipeline.OnStrain(older, &estimate));
  EXPECT_EQ(Strain(pipeline).out_of_order, 1);
  // A NaN reading is an arm without a reading, not a bad sample.
  MultiArmStrainSample missing = last;
  missing.utime += 1000;
  missing.seq += 1;
  missing.deflection_rad[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(pipeline.OnStrain(missing, &estimate));
  EXPECT_TRUE(std::isfinite(estimate.force_n[2]));
}

TEST(MultiArmPipelineTest, GapAndBackwardsJumpResetTheFilter) {
  const EstimatorConfig config = TrirotorConfig();
  const Recorded r = Hover(config);
  MultiArmPipeline pipeline(config);
  const size_t half = r.events.size() / 2;
  Feed(r, 0, half, &pipeline);
  // Skip 0.2 s of samples (reset_gap_s 0.1 s): a gap.
  size_t resume = half;
  const int64_t gap_until = pipeline.health().newest_utime + 200000;
  while (resume < r.events.size() && (r.events[resume].kind != 0 || r.events[resume].strain.utime < gap_until)) {
    ++resume;
  }
  const std::vector<MultiArmForceEstimate> after = Feed(r, resume, resume + 10, &pipeline);
  ASSERT_FALSE(after.empty());
  EXPECT_EQ(pipeline.health().resets, 2);
  EXPECT_EQ(pipeline.health().last_reset_reason, ResetReason::kGap);
  EXPECT_NE(after.front().status & kStatusFilterReset, 0);
  EXPECT_EQ(after.front().status & kStatusValid, 0);  // converging again
  // The log played again from its start: more than time_backwards_reset_s back.
  Feed(r, 0, 20, &pipeline);
  EXPECT_EQ(pipeline.health().resets, 3);
  EXPECT_EQ(pipeline.health().last_reset_reason, ResetReason::kTimeBackwards);
}

TEST(MultiArmPipelineTest, StaleMotorWithdrawsValid) {
  const EstimatorConfig config = TrirotorConfig();
  const Recorded r = Hover(config);
  MultiArmPipeline pipeline(config);
  std::vector<MultiArmForceEstimate> estimates;
  for (const Recorded::Event& e : r.events) {
    MultiArmForceEstimate estimate;
    if (e.kind == 1 && e.motor.utime < 1'000'000) pipeline.OnMotor(e.motor);  // MOTOR stops at 1 s
    if (e.kind == 2) pipeline.OnImu(e.imu);
    if (e.kind == 0 && pipeline.OnStrain(e.strain, &estimate)) estimates.push_back(estimate);
  }
  ASSERT_EQ(estimates.size(), 2000u);
  EXPECT_NE(estimates[900].status & kStatusValid, 0);
  // motor_timeout_s 0.05 s after the last MOTOR (at 0.998 s): INPUT_STALE, not VALID.
  EXPECT_NE(estimates.back().status & kStatusInputStale, 0);
  EXPECT_EQ(estimates.back().status & kStatusValid, 0);
}

size_t CountKind(const Recorded& r, int kind) {
  size_t n = 0;
  for (const Recorded::Event& e : r.events) n += e.kind == kind ? 1 : 0;
  return n;
}

int64_t Reports(const InputCounters& c) { return c.fused + c.rejected_gate + c.not_fused; }

TEST(MultiArmPipelineTest, EveryFusionReportIsCountedOnItsInput) {
  const EstimatorConfig config = TrirotorConfig();
  const Recorded r = Hover(config);
  MultiArmPipeline pipeline(config);
  Feed(r, 0, r.events.size(), &pipeline);
  const MultiArmPipelineHealth& h = pipeline.health();
  const InputCounters& strain = h.inputs[static_cast<int>(InputChannel::kStrain)];
  const InputCounters& motor = h.inputs[static_cast<int>(InputChannel::kMotor)];
  const InputCounters& imu = h.inputs[static_cast<int>(InputChannel::kImu)];
  const InputCounters& pose = h.inputs[static_cast<int>(InputChannel::kPose)];
  const InputCounters& accel = h.accelerometer;
  // One report per strain sample but the first (it initialises the
  // filter), per MOTOR sample, per IMU sample but the last (queued behind
  // the last strain sample); every one fused on this matching hover but
  // the accelerometer's first accel_noise_min_samples + 1 (an airborne
  // start: fused once its noise was learned from that many pairs, 6
  // samples).
  EXPECT_EQ(Reports(strain), static_cast<int64_t>(CountKind(r, 0)) - 1);
  EXPECT_EQ(strain.fused, Reports(strain));
  EXPECT_EQ(Reports(motor), static_cast<int64_t>(CountKind(r, 1)));
  EXPECT_EQ(Reports(imu), static_cast<int64_t>(CountKind(r, 2)) - 1);
  EXPECT_EQ(accel.received, static_cast<int64_t>(CountKind(r, 2)));
  const int64_t unlearned = config.ekf.accel_noise_min_samples + 1;
  EXPECT_EQ(accel.rejected_gate, unlearned);
  EXPECT_GE(accel.fused, accel.received - 2 - unlearned);
  EXPECT_EQ(Reports(pose), 0);
  // The mean NIS near its degrees of freedom: 3 gauges, a_z and a_x
  // (measured 2.90 and 2.02).
  ASSERT_EQ(strain.nis_count, strain.fused);
  EXPECT_NEAR(strain.nis_sum / static_cast<double>(strain.nis_count), 3.0, 0.5);
  EXPECT_NEAR(accel.nis_sum / static_cast<double>(accel.nis_count), 2.0, 0.5);
  EXPECT_EQ(accel.accepted_in_period, accel.received);
  EXPECT_EQ(strain.gate, config.ekf.strain_gate_nis);
  EXPECT_EQ(motor.gate, config.ekf.telemetry_gate_nis);
  EXPECT_EQ(imu.gate, config.ekf.gyro_gate_nis);
  EXPECT_EQ(accel.gate, config.ekf.accel_gate_nis);
  EXPECT_TRUE(std::isnan(pose.gate));
  pipeline.TakePeriod();  // after a status message: the period's NIS and rate start again
  EXPECT_EQ(strain.nis_count, 0);
  EXPECT_EQ(accel.nis_count, 0);
  EXPECT_EQ(accel.accepted_in_period, 0);
  EXPECT_EQ(strain.fused, 1999);  // the counts since start-up stay
}

}  // namespace
}  // namespace birotor
