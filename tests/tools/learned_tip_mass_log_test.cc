// Issue 36 item 4: `birotor-identify --update-params FILE --learned LOG`
// deploys the tip mass the flight's ESTIMATOR_LEARNED_N recorded. The
// birotor with tip masses 20 % above its file's
// (config/scenarios/mismatch_tip_mass_plus20.yaml) learns m_p in a first
// flight; a second flight resumes from the state file it left (two flights'
// readings: a re-run of the second log's inputs alone starts from the
// file's m_p) and its log deploys the m_p the estimator flew, with its
// sigma. Refused with one line naming the log and the key: a log flown with
// another vehicle and a recorded m_p out of the state file's ranges; a
// recorded m_p the log's inputs do not support is not used (the re-run's is).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "birotor/estimator_learned_n_t.hpp"
#include "model/vehicle_description_checksum.h"
#include "nodes/gauge_state_file.h"
#include "nodes/recorded_tip_mass.h"
#include "params/estimator_config_yaml.h"
#include "replay/learned_rerun.h"
#include "tests/estimator/scenario_harness.h"
#include "tests/tools/flight_log_recording.h"
#include "tests/tools/learned_deploy_support.h"
#include "transport/channels.h"
#include "transport/log_io.h"

namespace birotor {
namespace testing_support {
namespace {

constexpr double kTrueTipMassKg = 0.345744;  // the scenario's vehicle (1.2 x the file's 0.28812 kg)

Scenario Flight(int seed) {
  return LoadScenario(ScenarioFile("mismatch_tip_mass_plus20"), {"scenario.seed=" + std::to_string(seed)});
}

// A copy of log with `message` appended as one more ESTIMATOR_LEARNED_N
// (a forger on the bus), at path.
void AppendLearned(const std::string& log, const estimator_learned_n_t& message, const std::string& path) {
  const std::string tail = path + ".tail";
  LogWriter writer;
  std::string error;
  ASSERT_TRUE(writer.Open(tail, &error)) << error;
  ASSERT_TRUE(writer.WriteMessage(MakeChannelNames().estimator_learned_n, message.utime, message));
  ASSERT_TRUE(writer.Close());
  std::ofstream(path, std::ios::binary) << ReadText(log) << ReadText(tail);
  std::filesystem::remove(tail);
}

// An ESTIMATOR_LEARNED_N of the reference birotor with a learned m_p.
estimator_learned_n_t LearnedMessage(const EstimatorConfig& config, double tip_mass_kg, double std_kg) {
  estimator_learned_n_t m;
  m.utime = 16000000;
  m.vehicle_checksum = DescriptionChecksum(config.vehicle);
  m.n_arms = 2;
  m.strain_scale = {1.0, 1.0};
  m.strain_scale_std = {NAN, NAN};
  m.tip_mass_kg = {tip_mass_kg, tip_mass_kg};
  m.tip_mass_std_kg = {std_kg, std_kg};
  m.strain_noise_rad = {2e-5, 2e-5};
  m.tip_mass_source = "learned";
  m.strain_scale_source = m.strain_noise_source = m.body_mass_source = "params";
  m.body_mass_kg = 4.0;
  m.body_mass_std_kg = NAN;
  return m;
}

TEST(LearnedTipMassFromLog, TheResumedFlightsRecordedTipMassIsDeployed) {
  Folder folder;
  const std::string shipped = std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml";
  const std::string learning_file = folder.path + "/learning.yaml";
  WriteLearningConfig(learning_file);
  const EstimatorConfig learning = LoadEstimatorConfig(learning_file);
  const std::string first_log = folder.path + "/first.lcm", resumed_log = folder.path + "/resumed.lcm";
  const GaugeCalibration persisted = PersistedGaugeState(RecordFlightLog(Flight(13), learning, first_log));
  ASSERT_TRUE(persisted.has_tip_mass);
  RecordFlightLog(Flight(14), learning, resumed_log, nullptr, &persisted);
  RecordedTipMass recorded;
  std::string error, err;
  ASSERT_TRUE(ReadRecordedTipMass(resumed_log, MakeChannelNames().estimator_learned_n, &recorded, &error)) << error;
  EXPECT_EQ(recorded.source, "learned");  // refined by the second flight's readings
  EXPECT_LT(recorded.tip_mass_std_kg, persisted.tip_mass_std_kg);
  EXPECT_NEAR(recorded.tip_mass_kg, kTrueTipMassKg, 3.0 * recorded.tip_mass_std_kg + 0.005);
  // A re-run of the resumed flight's inputs alone starts from the file's m_p: a wider sigma.
  LearnedRerun rerun;
  ASSERT_TRUE(RelearnFromLog(resumed_log, learning, kDefaultChannelPrefix, 0.0, &rerun, &error)) << error;
  ASSERT_TRUE(rerun.learned.has_tip_mass);
  EXPECT_GT(rerun.learned.tip_mass_std_kg, recorded.tip_mass_std_kg);
  std::printf(
      "first flight %.6f +- %.6f kg; resumed flight: recorded %.6f +- %.6f kg, its inputs re-run %.6f +- %.6f kg\n",
      persisted.tip_mass_kg, persisted.tip_mass_std_kg, recorded.tip_mass_kg, recorded.tip_mass_std_kg,
      rerun.learned.tip_mass_kg, rerun.learned.tip_mass_std_kg);

  // The recorded m_p and its sigma (what the estimator flew), not the re-run's.
  const std::string params = folder.path + "/estimator.yaml";
  std::filesystem::copy_file(shipped, params);
  ASSERT_EQ(RunIdentify({"--update-params", params, "--learned", resumed_log, "--estimator-config", learning_file}), 0);
  const EstimatorConfig deployed = LoadEstimatorConfig(params);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(deployed.vehicle.arms[i].tip_mass_kg, recorded.tip_mass_kg, 1e-9);
  char stamp[96];
  std::snprintf(stamp, sizeof(stamp), "(learned %.6g +- %.6g)", recorded.tip_mass_kg, recorded.tip_mass_std_kg);
  EXPECT_NE(ReadText(params).find(stamp), std::string::npos) << stamp;

  // Flown with another vehicle (the file's body mass changed since): one line, nothing written.
  const std::string other = folder.path + "/other.yaml";
  std::string text = ReadText(shipped);
  text.replace(text.find("body_mass_kg: 4.0"), 17, "body_mass_kg: 4.1");
  std::ofstream(other) << text;
  EXPECT_EQ(
      RunIdentify({"--update-params", other, "--learned", resumed_log, "--estimator-config", learning_file}, &err), 1);
  EXPECT_NE(err.find("--learned " + resumed_log +
                     ": its newest ESTIMATOR_LEARNED_N with a learned tip_mass_kg was flown with another vehicle"),
            std::string::npos)
      << err;
  EXPECT_EQ(ReadText(other), text);

  // A recorded m_p outside the state file's range: refused, nothing written.
  const std::string wild_log = folder.path + "/wild.lcm", unchanged = folder.path + "/unchanged.yaml";
  std::filesystem::copy_file(shipped, unchanged);
  AppendLearned(first_log, LearnedMessage(learning, 150.0, 0.003), wild_log);
  EXPECT_EQ(
      RunIdentify({"--update-params", unchanged, "--learned", wild_log, "--estimator-config", learning_file}, &err), 1);
  EXPECT_NE(err.find(wild_log + ": its newest ESTIMATOR_LEARNED_N with a learned tip_mass_kg has tip_mass_kg 150 "
                                "outside [0.0001, 100] kg"),
            std::string::npos)
      << err;
  EXPECT_EQ(ReadText(unchanged), ReadText(shipped));

  // In range but not what the log's inputs support: not used, the re-run's deployed.
  const std::string forged_log = folder.path + "/forged.lcm", from_rerun = folder.path + "/rerun.yaml";
  std::filesystem::copy_file(shipped, from_rerun);
  AppendLearned(first_log, LearnedMessage(learning, 0.5, 0.001), forged_log);
  ASSERT_EQ(
      RunIdentify({"--update-params", from_rerun, "--learned", forged_log, "--estimator-config", learning_file}, &err),
      0);
  EXPECT_NE(err.find("tip_mass_kg: the log's ESTIMATOR_LEARNED_N says 0.5 +- 0.001 kg, its inputs re-run give"),
            std::string::npos)
      << err;
  EXPECT_NEAR(LoadEstimatorConfig(from_rerun).vehicle.arms[0].tip_mass_kg, persisted.tip_mass_kg, 1e-9);
}

// The checks one by one, on recorded values.
TEST(LearnedTipMassFromLog, EachRefusalNamesTheLogAndTheKey) {
  const EstimatorConfig config = LoadEstimatorConfig(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");
  RecordedTipMass recorded;
  recorded.tip_mass_kg = recorded.other_arm_kg = 0.34;
  recorded.tip_mass_std_kg = 0.003;
  recorded.n_arms = 2;
  recorded.source = "state_file";
  recorded.vehicle_checksum = DescriptionChecksum(config.vehicle);
  EXPECT_EQ(RecordedTipMassRefusal("f.lcm", recorded, config.vehicle, "p.yaml"), "");
  RecordedTipMass wide = recorded;
  wide.tip_mass_std_kg = 2.0;
  EXPECT_EQ(RecordedTipMassRefusal("f.lcm", wide, config.vehicle, "p.yaml"),
            "--learned f.lcm: its newest ESTIMATOR_LEARNED_N with a learned tip_mass_kg has tip_mass_std_kg 2 outside "
            "[1e-06, 1] kg: refused, nothing written");
  RecordedTipMass split = recorded;
  split.other_arm_kg = 0.3;
  EXPECT_NE(RecordedTipMassRefusal("f.lcm", split, config.vehicle, "p.yaml").find("is not one m_p for both arms"),
            std::string::npos);
  RecordedTipMass foreign = recorded;
  foreign.vehicle_checksum = "0123456789abcdef";
  EXPECT_NE(RecordedTipMassRefusal("f.lcm", foreign, config.vehicle, "p.yaml")
                .find("was flown with another vehicle or parameter file (vehicle checksum '0123456789abcdef', p.yaml "
                      "now "),
            std::string::npos);

  // Not learned: a log whose ESTIMATOR_LEARNED_N all say params.
  Folder folder;
  const std::string log = folder.path + "/params.lcm";
  estimator_learned_n_t message = LearnedMessage(config, 0.28812, NAN);
  message.tip_mass_source = "params";
  LogWriter writer;
  std::string error;
  ASSERT_TRUE(writer.Open(log, &error)) << error;
  ASSERT_TRUE(writer.WriteMessage(MakeChannelNames().estimator_learned_n, message.utime, message));
  ASSERT_TRUE(writer.Close());
  EXPECT_FALSE(ReadRecordedTipMass(log, MakeChannelNames().estimator_learned_n, &recorded, &error));
  EXPECT_EQ(error,
            log +
                ": no BIROTOR_ESTIMATOR_LEARNED_N message with a learned tip_mass_kg (1 messages, 0 undecodable; the "
                "estimator learns it with model_consistency arm_mode_learn_tip_mass on)");
}

}  // namespace
}  // namespace testing_support
}  // namespace birotor
