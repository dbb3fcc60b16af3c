// ESTIMATOR_STATUS building and processing-time statistics.
#include "nodes/status_message.h"

#include <gtest/gtest.h>

#include <cmath>

#include "transport/lcm_codec.h"

namespace birotor {
namespace {

TEST(ProcessingTimeStatsTest, MeanP99MaxOverThePeriod) {
  ProcessingTimeStats stats;
  EXPECT_TRUE(std::isnan(stats.MeanUs()));
  EXPECT_TRUE(std::isnan(stats.P99Us()));
  for (int i = 1; i <= 1000; ++i) stats.Add(static_cast<double>(i));
  EXPECT_DOUBLE_EQ(stats.MeanUs(), 500.5);
  EXPECT_DOUBLE_EQ(stats.MaxUs(), 1000.0);
  EXPECT_DOUBLE_EQ(stats.P99Us(), 990.0);
  stats.TakePeriod();
  EXPECT_TRUE(std::isnan(stats.MaxUs()));
  stats.Add(7.0);
  EXPECT_DOUBLE_EQ(stats.P99Us(), 7.0);
}

TEST(ProcessingTimeStatsTest, PercentileUsesTheNewestSamplesWhenTheRingWraps) {
  ProcessingTimeStats stats;
  for (int i = 0; i < ProcessingTimeStats::kCapacity; ++i) stats.Add(1000.0);
  for (int i = 0; i < ProcessingTimeStats::kCapacity; ++i) stats.Add(1.0);
  EXPECT_DOUBLE_EQ(stats.P99Us(), 1.0);
  EXPECT_DOUBLE_EQ(stats.MaxUs(), 1000.0);  // the max is exact over the period
}

TEST(StatusMessageTest, CarriesCountersRatesAndAges) {
  PipelineHealth health;
  health.newest_utime = 3'000'000;
  InputCounters& strain = health.inputs[static_cast<int>(InputChannel::kStrain)];
  strain.received = 10;
  strain.fused = 7;
  strain.decode_errors = 2;
  strain.gaps = 1;
  strain.missing_samples = 4;
  strain.last_utime = 2'500'000;
  strain.accepted_in_period = 100;
  health.resets = 2;
  health.last_reset_reason = ResetReason::kGap;
  strain.nis_sum = 6.0;
  strain.nis_count = 3;
  strain.nis_max = 4.0;
  strain.gate = 30;
  strain.not_fused = 3;
  strain.time_outliers = 1;
  strain.conflicts = 2;
  strain.conflict_active = true;
  health.last_estimate.force_n[1] = 21.5;
  StatusContext context;
  context.period_s = 0.2;
  context.seq = 5;
  estimator_status_t message;
  BuildStatusMessage(health, "ekf", context, &message);
  EXPECT_EQ(message.seq, 5);
  EXPECT_EQ(message.num_inputs, 4);
  ASSERT_EQ(message.inputs.size(), 4u);
  EXPECT_EQ(message.inputs[0].channel, "STRAIN");
  EXPECT_EQ(message.inputs[3].channel, "POSE");
  EXPECT_EQ(message.inputs[0].decode_errors, 2);
  EXPECT_EQ(message.inputs[0].missing_samples, 4);
  EXPECT_DOUBLE_EQ(message.inputs[0].age_s, 0.5);
  EXPECT_DOUBLE_EQ(message.inputs[0].rate_hz, 500.0);
  EXPECT_TRUE(std::isnan(message.inputs[1].age_s));  // never received
  EXPECT_DOUBLE_EQ(message.strain_nis_mean, 2.0);
  EXPECT_DOUBLE_EQ(message.strain_nis_max, 4.0);
  EXPECT_DOUBLE_EQ(message.strain_gate, 30.0);
  EXPECT_DOUBLE_EQ(message.inputs[0].nis_mean, 2.0);
  EXPECT_DOUBLE_EQ(message.inputs[0].gate, 30.0);
  EXPECT_TRUE(std::isnan(message.inputs[1].nis_mean));  // no report this period
  EXPECT_EQ(message.inputs[0].not_fused, 3);
  EXPECT_EQ(message.inputs[0].time_outliers, 1);
  EXPECT_EQ(message.inputs[0].conflicts, 2);
  EXPECT_EQ(message.inputs[0].conflict_active, 1);
  EXPECT_EQ(message.last_reset_reason, "gap");
  EXPECT_DOUBLE_EQ(message.force_n[1], 21.5);
  // The message encodes and decodes through the checked codec.
  std::vector<uint8_t> buffer;
  EncodeMessage(message, &buffer);
  estimator_status_t decoded;
  ASSERT_EQ(DecodeMessage(buffer.data(), buffer.size(), &decoded), DecodeError::kNone);
  EXPECT_EQ(decoded.inputs[0].fused, 7);
}

// ESTIMATOR_STATUS of an EKF with `health`, through the wire and back.
bool BuildEncodeDecode(const PipelineHealth& health, estimator_status_t* decoded) {
  estimator_status_t message;
  BuildStatusMessage(health, "ekf", StatusContext(), &message);
  std::vector<uint8_t> buffer;
  EncodeMessage(message, &buffer);
  return DecodeMessage(buffer.data(), buffer.size(), decoded) == DecodeError::kNone;
}

TEST(StatusMessageTest, CarriesTheGaugeOffsetsAndTheTareCounters) {
  PipelineHealth health;
  health.gauge.offset_rad[0] = 1.5e-5;
  health.gauge.offset_std_rad[1] = 1.1e-6;
  health.gauge.source = GaugeOffsetSource::kTare;
  health.tare.accepted = 3;
  health.tare.refused_body_moving = 2;
  health.tare.refused_out_of_range = 1;
  health.tare.last_refusal = TareRefusal::kOutOfRange;
  estimator_status_t decoded;
  ASSERT_TRUE(BuildEncodeDecode(health, &decoded));
  EXPECT_EQ(decoded.gauge_offset_rad[0], 1.5e-5);
  EXPECT_EQ(decoded.gauge_offset_std_rad[1], 1.1e-6);
  EXPECT_EQ(decoded.gauge_offset_source, "tare");
  EXPECT_EQ(decoded.tares, 3);
  EXPECT_EQ(decoded.tares_refused_motors_running, 0);
  EXPECT_EQ(decoded.tares_refused_body_moving, 2);
  EXPECT_EQ(decoded.tares_refused_out_of_range, 1);
  EXPECT_EQ(decoded.last_tare_refusal, "out_of_range");
}

TEST(StatusMessageTest, CarriesTheModelConsistencyStatisticAndParameter) {
  PipelineHealth health;
  health.consistency.statistic = 3.25;
  health.consistency.mismatch = true;
  health.consistency.parameter = MismatchParameter::kMass;
  estimator_status_t decoded;
  ASSERT_TRUE(BuildEncodeDecode(health, &decoded));
  EXPECT_EQ(decoded.model_consistency_statistic, 3.25);
  EXPECT_EQ(decoded.mismatch_parameter, "mass");
}

// A fast raise (the accelerometer's CUSUM) comes 11 ms after the start, before
// the first 0.25 s window closes: the statistic published is the fast test's,
// not the window's 0 (docs/mismatch.md).
TEST(StatusMessageTest, AFastRaiseReportsTheFastTestsStatistic) {
  PipelineHealth health;
  health.consistency.statistic = 0.0;
  health.consistency.fast_statistic = 1.7;
  health.consistency.mismatch = true;
  health.consistency.raised_fast = true;
  health.consistency.parameter = MismatchParameter::kStiffnessOrGaugeScale;
  estimator_status_t decoded;
  ASSERT_TRUE(BuildEncodeDecode(health, &decoded));
  EXPECT_EQ(decoded.model_consistency_statistic, 1.7);
  EXPECT_EQ(decoded.mismatch_parameter, "stiffness_or_gauge_scale");
}

TEST(StatusMessageTest, NotLearnedParametersAreTheFilesWithNanSigma) {
  PipelineHealth health;
  health.body_mass_kg = 4.0;  // config/reference_vehicle.yaml body_mass_kg
  estimator_status_t decoded;
  ASSERT_TRUE(BuildEncodeDecode(health, &decoded));
  for (int arm = 0; arm < 2; ++arm) {
    EXPECT_EQ(decoded.strain_scale[arm], 1.0);
    EXPECT_TRUE(std::isnan(decoded.strain_scale_std[arm]));
  }
  EXPECT_EQ(decoded.strain_scale_source, "params");
  EXPECT_EQ(decoded.body_mass_kg, 4.0);
  EXPECT_TRUE(std::isnan(decoded.body_mass_std_kg));
  EXPECT_EQ(decoded.body_mass_source, "params");
}

TEST(StatusMessageTest, CarriesTheLearnedStrainScalesAndBodyMassWithTheirSource) {
  PipelineHealth health;
  health.gauge.has_strain_scale = true;
  health.gauge.strain_scale[0] = 0.71;
  health.gauge.strain_scale[1] = 1.02;
  health.gauge.strain_scale_std[0] = 0.004;
  health.gauge.strain_scale_std[1] = 0.005;
  health.body_mass_learned = true;
  health.body_mass_kg = 4.6;
  health.body_mass_std_kg = 0.03;
  estimator_status_t decoded;
  ASSERT_TRUE(BuildEncodeDecode(health, &decoded));
  EXPECT_EQ(decoded.strain_scale[0], 0.71);
  EXPECT_EQ(decoded.strain_scale[1], 1.02);
  EXPECT_EQ(decoded.strain_scale_std[0], 0.004);
  EXPECT_EQ(decoded.strain_scale_std[1], 0.005);
  EXPECT_EQ(decoded.strain_scale_source, "learned");
  EXPECT_EQ(decoded.body_mass_kg, 4.6);
  EXPECT_EQ(decoded.body_mass_std_kg, 0.03);
  EXPECT_EQ(decoded.body_mass_source, "learned");
  health.strain_scale_from_state_file = true;  // learning started from an earlier run's value
  ASSERT_TRUE(BuildEncodeDecode(health, &decoded));
  EXPECT_EQ(decoded.strain_scale_source, "state_file");
  // The vehicle the values are relative to, as the context gives it.
  StatusContext context;
  context.vehicle_checksum = "913d0fa3ed23d161";
  estimator_status_t message;
  BuildStatusMessage(health, "ekf", context, &message);
  EXPECT_EQ(message.vehicle_checksum, "913d0fa3ed23d161");
}

TEST(StatusMessageTest, EveryInputHasItsGateAndTheBaselinesNone) {
  EstimatorConfig config;
  EXPECT_EQ(GateOf(config, InputChannel::kStrain), config.ekf.strain_gate_nis);
  EXPECT_EQ(GateOf(config, InputChannel::kMotor), config.ekf.telemetry_gate_nis);
  EXPECT_EQ(GateOf(config, InputChannel::kImu), config.ekf.gyro_gate_nis);
  EXPECT_TRUE(std::isnan(GateOf(config, InputChannel::kPose)));
  config.method = "motor_map";
  EXPECT_TRUE(std::isnan(GateOf(config, InputChannel::kStrain)));
}

TEST(StatusMessageTest, AgeIsNanForASampleNewerThanTheClock) {
  PipelineHealth health;
  health.newest_utime = 1'000'000;
  health.inputs[static_cast<int>(InputChannel::kPose)].last_utime = (int64_t{1} << 53) - 1;
  estimator_status_t message;
  BuildStatusMessage(health, "ekf", StatusContext{}, &message);
  EXPECT_EQ(message.utime, 1'000'000);
  EXPECT_TRUE(std::isnan(message.inputs[static_cast<int>(InputChannel::kPose)].age_s));
}

}  // namespace
}  // namespace birotor
