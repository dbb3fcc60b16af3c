// The N-arm linear KF and Luenberger observer judged by the pipeline's
// model-consistency monitor (their fusion reports, estimator/multi_arm_linear_estimator.h):
// a vehicle that differs from its description is raised instead of VALID,
// the matching one from the ground is not, and the gyro is fused again after
// a lift-off. On the trirotor description, simulated flights; figures
// measured on this commit.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include "estimator/estimation_method.h"
#include "estimator/multi_arm_linear_estimator.h"
#include "evaluation/multi_arm_accuracy.h"
#include "multi_arm_source_files.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "samples/sample_sink.h"
#include "simulator/multi_arm_simulator.h"

namespace birotor {
namespace {

EstimatorConfig TrirotorConfig(const std::string& method) {
  EstimatorConfig config = Config();
  config.vehicle = Vehicle("trirotor");
  config.method = method;
  return config;
}

void Print(const std::string& label, const MultiArmAccuracy& r) {
  std::printf("%s: MAE %.4f / %.4f / %.4f N, 2-sigma %.3f / %.3f / %.3f, VALID %.3f, MODEL_MISMATCH %.3f\n",
              label.c_str(), r.rotor[0].mae_n, r.rotor[1].mae_n, r.rotor[2].mae_n, r.rotor[0].share_within_2sigma,
              r.rotor[1].share_within_2sigma, r.rotor[2].share_within_2sigma, r.valid_share, r.mismatch_share);
}

// Every tip mass 20 % heavier than the description, 8 s of gentle flight
// (seed 1). Measured, linear_kf and luenberger alike: MODEL_MISMATCH 0.953
// of the scored estimates, VALID 0.047 (until the arm-mode test's first
// reading); the forces 0.53 / 0.37 / 0.37 N off, within their sigma (the tip
// mass's prior). Before the methods reported their fusions they were not
// judged: VALID 1.000 and 2-sigma share 0.003 - 0.018. Asserted: raised on
// more than 0.8 of the flight, VALID below 0.2.
TEST(MultiArmLinearConsistencyTest, TipMassErrorIsRaisedNotValid) {
  for (const char* method : {"linear_kf", "luenberger"}) {
    const EstimatorConfig config = TrirotorConfig(method);
    VehicleDescription heavier_tips = config.vehicle;
    for (int i = 0; i < heavier_tips.arm_count; ++i) heavier_tips.arms[static_cast<size_t>(i)].tip_mass_kg *= 1.2;
    const Scenario gentle = ScenarioFor("gentle", {"scenario.duration_s=8", "scenario.seed=1"}, 3);
    const MultiArmAccuracy r = RunMultiArmAccuracyFlying(heavier_tips, gentle, config, EvalOptions());
    Print(std::string(method) + " tip mass +20 %", r);
    EXPECT_GT(r.mismatch_share, 0.8) << method;
    EXPECT_LT(r.valid_share, 0.2) << method;
    EXPECT_EQ(r.nonfinite, 0) << method;
  }
}

// Gauge 2 reading 1.3 of its scale (the simulator's gauge; the description
// says 1), 4 s of gentle flight. Measured: MODEL_MISMATCH 1.000, VALID 0.000
// for both methods (rotor 2 5.18 / 5.30 N off); before: VALID 1.000, 2-sigma share
// 0.000. Asserted: raised on more than 0.9 of the flight.
TEST(MultiArmLinearConsistencyTest, OneGaugeReadingHighIsRaised) {
  for (const char* method : {"linear_kf", "luenberger"}) {
    const MultiArmAccuracy r = RunMultiArmAccuracy(
        Vehicle("trirotor"), ScenarioFor("gentle", {"scenario.duration_s=4", "gauge.scale=[1.0, 1.3, 1.0]"}, 3),
        TrirotorConfig(method), EvalOptions());
    Print(std::string(method) + " gauge 2 x1.3", r);
    EXPECT_GT(r.mismatch_share, 0.9) << method;
    EXPECT_LT(r.valid_share, 0.1) << method;
  }
}

// The matching trirotor from the ground (gentle, 15 s): the held body is
// not judged as the hover model's (body_supported: forces below half the
// hover's; the gyro not fused there). Measured: linear_kf MAE 0.0870 /
// 0.0609 / 0.0607 N, 2-sigma 0.942 / 0.991 / 0.994, VALID 1.000,
// MODEL_MISMATCH 0.000; luenberger 0.0978 / 0.0757 / 0.0750 N, VALID 1.000,
// MODEL_MISMATCH 0.000 (judged from the ground like in the air: 1.000 /
// 0.194 before the two rules). Asserted: no MODEL_MISMATCH, VALID above
// 0.99, MAE below 1.3x.
TEST(MultiArmLinearConsistencyTest, MatchingGroundStartIsNotRaised) {
  const double measured_mae_n[2][3] = {{0.0870, 0.0609, 0.0607}, {0.0978, 0.0757, 0.0750}};
  int m = 0;
  for (const char* method : {"linear_kf", "luenberger"}) {
    const MultiArmAccuracy r = RunMultiArmAccuracy(
        Vehicle("trirotor"), ScenarioFor("gentle", {"ground.enabled=true"}, 3), TrirotorConfig(method), EvalOptions());
    Print(std::string(method) + " gentle from the ground", r);
    EXPECT_EQ(r.mismatch_share, 0.0) << method;
    EXPECT_GT(r.valid_share, 0.99) << method;
    for (size_t i = 0; i < 3; ++i) EXPECT_LT(r.rotor[i].mae_n, 1.3 * measured_mae_n[m][i]) << method << " rotor " << i;
    ++m;
  }
}

// Counts the gyro's fusion reports of a linear KF fed by the simulator,
// from the first estimate with the body free after it was held.
class GyroAfterLiftOff : public SampleSink {
 public:
  explicit GyroAfterLiftOff(MultiArmForceEstimator* filter) : filter_(filter) {}
  void OnStrainN(const MultiArmStrainSample& sample) override {
    MultiArmForceEstimate estimate;
    filter_->AddStrain(sample, &estimate);
    held_ = held_ || filter_->body_supported();
    lifted_ = lifted_ || (held_ && !filter_->body_supported());
    if (!lifted_) return;
    for (const FusionReport& report : *filter_->reports()) {
      if (report.source != FusionSource::kGyro) continue;
      ++gyro_;
      fused_ += report.outcome == FusionOutcome::kFused;
    }
  }
  void OnMotorN(const MultiArmMotorSample& sample) override { filter_->AddMotor(sample); }
  void OnImu(const ImuSample& sample) override { filter_->AddImu(sample); }
  bool held() const { return held_; }
  int64_t gyro() const { return gyro_; }
  int64_t fused() const { return fused_; }

 private:
  MultiArmForceEstimator* filter_;
  bool held_ = false, lifted_ = false;
  int64_t gyro_ = 0, fused_ = 0;
};

// The lift-off's thrust ramp leaves the hover model's pitch rate rad/s off
// (1.75 rad/s predicted against 0.01 measured); without the gyro gate's
// inflation every later gyro sample was gated for the rest of the flight.
// Measured (gentle from the ground, 15 s): after the lift-off 10 971 gyro
// reports, 10 966 fused. Asserted: more than 0.99 fused.
TEST(MultiArmLinearConsistencyTest, GyroIsFusedAgainAfterALiftOff) {
  const EstimatorConfig config = TrirotorConfig("linear_kf");
  EstimationMethod method;
  ASSERT_TRUE(ParseEstimationMethod("linear_kf", &method));
  std::unique_ptr<MultiArmForceEstimator> filter = MakeMultiArmForceEstimator(method, config);
  MultiArmSimulator simulator(config.vehicle, ScenarioFor("gentle", {"ground.enabled=true"}, 3));
  GyroAfterLiftOff sink(filter.get());
  simulator.Run(&sink);
  std::printf("gyro after the lift-off: %lld reports, %lld fused\n", static_cast<long long>(sink.gyro()),
              static_cast<long long>(sink.fused()));
  ASSERT_TRUE(sink.held());
  ASSERT_GT(sink.gyro(), 5000);
  EXPECT_GT(static_cast<double>(sink.fused()), 0.99 * static_cast<double>(sink.gyro()));
}

}  // namespace
}  // namespace birotor
