// Issue 36 item 4: the tip mass the arm-mode test learned resumes from the
// gauge state file at the next start. A flight of the birotor with tip
// masses 20 % above its file's (config/scenarios/mismatch_tip_mass_plus20.yaml)
// learns m_p (model_consistency.arm_mode_learn_tip_mass); the daemon's
// state at its stop (PersistedGaugeState) goes through the authenticated
// state file and back (its checks: mac, vehicle checksum, ranges); a
// restart (another seed of the flight) from it flies the persisted m_p
// with the persisted sigma from the first estimate (ESTIMATOR_LEARNED_N
// source state_file until this run's first reading, learned after), and its
// first second is as accurate as the end of the learning flight. With
// learning off the persisted m_p is not flown (the file's, source params)
// and the stop does not write it back, as a persisted strain scale with
// learn_strain_scale off.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "birotor/estimator_learned_n_t.hpp"
#include "birotor/estimator_status_t.hpp"
#include "nodes/estimator_learned_message.h"
#include "nodes/gauge_state_file.h"
#include "security/message_authenticator.h"
#include "security/site_key.h"
#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace testing_support {
namespace {

constexpr double kFileTipMassKg = 0.28812;   // config/reference_vehicle.yaml
constexpr double kTrueTipMassKg = 0.345744;  // 1.2 x: the scenario's vehicle

EstimatorConfig LearningConfig(bool learn) {
  EstimatorConfig config = ReferenceConfig();
  config.model_consistency.arm_mode_learn_tip_mass = learn;
  return config;
}

// The tip mass as ESTIMATOR_LEARNED_N carries it at one estimate.
struct TipMassSample {
  double kg = 0, std_kg = 0;
  std::string source;
};

// PairingSink, and what ESTIMATOR_LEARNED_N would say after every estimate.
class TipMassSink : public PairingSink {
 public:
  TipMassSink(EstimatorPipeline* pipeline, const EstimatorConfig& config)
      : PairingSink(pipeline), pipeline_(pipeline), config_(config) {
    PrepareEstimatorLearned(config.vehicle, &message_);
  }
  void OnStrain(const StrainSample& s) override {
    PairingSink::OnStrain(s);
    FillEstimatorLearned(pipeline_->health(), config_, estimator_status_t(), &message_);
    samples.push_back({message_.tip_mass_kg[0], message_.tip_mass_std_kg[0], message_.tip_mass_source});
  }
  std::vector<TipMassSample> samples;  // after every strain sample

 private:
  EstimatorPipeline* pipeline_;
  EstimatorConfig config_;
  estimator_learned_n_t message_;
};

struct Flight {
  ScenarioRun run;
  std::vector<TipMassSample> tip_mass;
};

// The flight (seed: scenario.seed) from the state `persisted` (nullptr: a first start).
Flight Fly(const EstimatorConfig& config, int seed, const GaugeCalibration* persisted,
           const std::string& scenario = "mismatch_tip_mass_plus20") {
  EstimatorPipeline pipeline(config);
  if (persisted != nullptr) pipeline.SetGaugeOffsets(*persisted);
  TipMassSink sink(&pipeline, config);
  Simulator simulator(LoadScenario(ScenarioFile(scenario), {"scenario.seed=" + std::to_string(seed)}));
  simulator.Run(&sink);
  sink.run.health = pipeline.health();
  return {sink.run, sink.samples};
}

// The worse rotor's MAE over [from_s, to_s) of the flight's estimates [N].
double Mae(const ScenarioRun& run, double from_s, double to_s) {
  const int64_t start = run.forces.front().utime;
  double sum[2] = {0, 0};
  int64_t count = 0;
  for (const PairedSample& p : run.pairs) {
    const double t_s = (p.utime - start) * 1e-6;
    if (t_s < from_s || t_s >= to_s) continue;
    for (int i = 0; i < 2; ++i) sum[i] += std::abs(p.force_error_n[i]);
    ++count;
  }
  return count > 0 ? std::max(sum[0], sum[1]) / static_cast<double>(count) : NAN;
}

// The daemon's stop and start: the state through the authenticated file.
GaugeCalibration ThroughStateFile(const PipelineHealth& health, const EstimatorConfig& config) {
  const std::string path = ::testing::TempDir() + "/tip_mass_resume_" + std::to_string(getpid()) + ".state";
  SiteKey::Bytes bytes;
  bytes.fill(0x5a);
  const MessageAuthenticator authenticator{SiteKey(bytes)};
  const std::string vehicle = VehicleChecksum(BirotorModelOf(config.vehicle));
  std::string error;
  EXPECT_TRUE(WriteGaugeState(path, PersistedGaugeState(health), vehicle, authenticator, &error)) << error;
  GaugeCalibration read = GaugeCalibration::FromVehicle(BirotorModelOf(config.vehicle));
  EXPECT_TRUE(ReadGaugeState(path, vehicle, config.tare.max_offset_rad, authenticator, &read, &error)) << error;
  std::remove(path.c_str());
  return read;
}

TEST(TipMassResume, ARestartFliesThePersistedTipMassFromItsFirstEstimate) {
  const EstimatorConfig learning = LearningConfig(true);
  const Flight first = Fly(learning, 13, nullptr);
  const GaugeCalibration persisted = ThroughStateFile(first.run.health, learning);
  ASSERT_TRUE(persisted.has_tip_mass);
  EXPECT_NEAR(persisted.tip_mass_kg, kTrueTipMassKg, 3.0 * persisted.tip_mass_std_kg + 0.005);
  EXPECT_LT(persisted.tip_mass_std_kg, 0.25 * 0.15 * kFileTipMassKg);  // well below the prior's

  // The restart: another flight of that vehicle, from the state file.
  const Flight resumed = Fly(learning, 14, &persisted);
  ASSERT_FALSE(resumed.tip_mass.empty());
  const TipMassSample& at_start = resumed.tip_mass.front();
  EXPECT_EQ(at_start.source, "state_file");
  EXPECT_DOUBLE_EQ(at_start.kg, persisted.tip_mass_kg);
  EXPECT_NEAR(at_start.std_kg, persisted.tip_mass_std_kg, 1e-12);
  // state_file until this run's first reading, learned (refined) after.
  size_t first_learned = resumed.tip_mass.size();
  for (size_t k = 0; k < resumed.tip_mass.size(); ++k) {
    if (resumed.tip_mass[k].source == "learned" && first_learned == resumed.tip_mass.size()) first_learned = k;
    if (k >= first_learned) EXPECT_EQ(resumed.tip_mass[k].source, "learned") << k;
    if (k < first_learned) EXPECT_DOUBLE_EQ(resumed.tip_mass[k].kg, persisted.tip_mass_kg) << k;
  }
  ASSERT_LT(first_learned, resumed.tip_mass.size());
  EXPECT_GT(first_learned, 100u);  // the first reading needs the settling time and a time constant (0.6 s)
  const TipMassSample& at_end = resumed.tip_mass.back();
  EXPECT_NEAR(at_end.kg, kTrueTipMassKg, 3.0 * at_end.std_kg + 0.005);
  EXPECT_LT(at_end.std_kg, persisted.tip_mass_std_kg);  // two flights' readings
  EXPECT_TRUE(resumed.run.health.tip_mass_learned);

  // The same restart without the state file learns again from the file's m_p.
  const Flight fresh = Fly(learning, 14, nullptr);
  EXPECT_EQ(fresh.tip_mass.front().source, "params");  // learned from the first airborne sample the test judges
  EXPECT_DOUBLE_EQ(fresh.tip_mass.front().kg, kFileTipMassKg);
  const double end_of_learning = Mae(first.run, 14.0, 15.0);
  const double resumed_first_s = Mae(resumed.run, 0.0, 1.0), fresh_first_s = Mae(fresh.run, 0.0, 1.0);
  std::printf(
      "persisted %.6f +- %.6f kg, end of the resumed flight %.6f +- %.6f kg; worse rotor's MAE: learning flight "
      "14-15 s %.4f N, restart 0-1 s from the state file %.4f N, from the file's m_p %.4f N; source state_file for "
      "the first %zu estimates\n",
      persisted.tip_mass_kg, persisted.tip_mass_std_kg, at_end.kg, at_end.std_kg, end_of_learning, resumed_first_s,
      fresh_first_s, first_learned);
  EXPECT_LT(resumed_first_s, 1.5 * end_of_learning);
  EXPECT_LT(resumed_first_s, 0.3 * fresh_first_s);
}

// The vehicle changed since the state file was written: the tips 20 %
// heavier then, the file's now (gentle). The readings reject the resumed
// m_p, and learning restarts from the file's m_p and the prior. Measured:
// rejected, the flight ends at 0.288092 +- 0.000377 kg, MAE 5-15 s 0.0690 N;
// without the rejection the learner, sure of the resumed value (sigma
// 1.1 %), ended at 0.310265 +- 0.002157 kg (10 sigma off), MAE 0.2869 N.
TEST(TipMassResume, AVehicleChangedSinceTheStateFileIsLearnedAfresh) {
  const EstimatorConfig learning = LearningConfig(true);
  const Flight first = Fly(learning, 13, nullptr);
  const GaugeCalibration persisted = ThroughStateFile(first.run.health, learning);
  ASSERT_TRUE(persisted.has_tip_mass);
  const Flight changed = Fly(learning, 14, &persisted, "gentle");
  const ArmModeState& arm = changed.run.health.consistency.arm_mode;
  const TipMassSample& at_end = changed.tip_mass.back();
  const double mae_from_5_s = Mae(changed.run, 5.0, 15.0);
  std::printf("resumed %.6f kg on the file's vehicle: rejected %d, end %.6f +- %.6f kg, MAE 5-15 s %.4f N\n",
              persisted.tip_mass_kg, arm.resumed_tip_mass_rejected, at_end.kg, at_end.std_kg, mae_from_5_s);
  EXPECT_TRUE(arm.resumed_tip_mass_rejected);
  EXPECT_EQ(at_end.source, "learned");
  EXPECT_NEAR(at_end.kg, kFileTipMassKg, 3.0 * at_end.std_kg + 0.005);
  EXPECT_LE(mae_from_5_s, 0.10);  // issue 36's target from 5 s on
  // The vehicle the state file describes: confirmed, never rejected.
  EXPECT_FALSE(Fly(learning, 14, &persisted).run.health.consistency.arm_mode.resumed_tip_mass_rejected);
}

TEST(TipMassResume, WithLearningOffThePersistedTipMassIsNotFlown) {
  const EstimatorConfig learning = LearningConfig(true);
  const Flight first = Fly(learning, 13, nullptr);
  const GaugeCalibration persisted = ThroughStateFile(first.run.health, learning);
  ASSERT_TRUE(persisted.has_tip_mass);
  const EstimatorConfig off = LearningConfig(false);
  EstimatorPipeline pipeline(off);
  pipeline.SetGaugeOffsets(persisted);
  EXPECT_FALSE(pipeline.health().tip_mass_learned);
  EXPECT_FALSE(pipeline.health().tip_mass_from_state_file);
  EXPECT_DOUBLE_EQ(pipeline.health().tip_mass_kg, kFileTipMassKg);
  const Flight flown = Fly(off, 14, &persisted);
  for (const TipMassSample& s : flown.tip_mass) {
    EXPECT_EQ(s.source, "params");
    EXPECT_DOUBLE_EQ(s.kg, kFileTipMassKg);
  }
  EXPECT_FALSE(PersistedGaugeState(flown.run.health).has_tip_mass);  // not written back at the stop
  // Learning the strain scales as well: the tip mass is learned beside them
  // (the arm mode tells a stiffness from a tip mass), so the persisted one is
  // flown and learning resumes from it.
  EstimatorConfig scales = learning;
  scales.ekf.learn_strain_scale = true;
  EstimatorPipeline with_scales(scales);
  with_scales.SetGaugeOffsets(persisted);
  EXPECT_TRUE(with_scales.health().tip_mass_learned);
  EXPECT_TRUE(with_scales.health().tip_mass_from_state_file);
  // Without the arm mode the scales alone cannot tell a tip mass: not flown.
  scales.model_consistency.arm_mode_learn_tip_mass = false;
  EstimatorPipeline without_mode(scales);
  without_mode.SetGaugeOffsets(persisted);
  EXPECT_FALSE(without_mode.health().tip_mass_learned);
  EXPECT_DOUBLE_EQ(without_mode.health().tip_mass_kg, kFileTipMassKg);
}

}  // namespace
}  // namespace testing_support
}  // namespace birotor
