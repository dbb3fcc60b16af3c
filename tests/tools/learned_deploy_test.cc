// Issue 27 item 2 end to end: a mismatched vehicle (config/scenarios/
// mismatch_gauge_scale_0p7.yaml, mismatch_stiffness_plus20.yaml,
// mismatch_payload_plus15.yaml) is flown with learning on, recorded as on the
// vehicle (the lock-step simulator's inputs and the estimator's FORCE and
// ESTIMATOR_STATUS in one log); the state file it leaves (under the site
// key) or the log is deployed with `birotor-identify --update-params COPY
// --learned STATE|LOG` into a copy of config/estimator.yaml; the EKF WITHOUT
// learning on the updated copy is then as accurate on that vehicle as with
// the true file (docs/identification.md, "Deploying what the estimator
// learned"). Issue 37 item 4: a forged or unsigned state file is refused, and
// a forged ESTIMATOR_STATUS appended to the log is not deployed (the log's
// inputs are re-run). Figures measured on the development VM (2 cores);
// bounds at most 1.5x.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "nodes/gauge_state_file.h"
#include "nodes/status_message.h"
#include "params/estimator_config_yaml.h"
#include "replay/replayer.h"
#include "security/message_authenticator.h"
#include "security/site_key.h"
#include "sinks/message_sink.h"
#include "sinks/wire_sample_sink.h"
#include "tests/estimator/scenario_harness.h"
#include "tests/tools/flight_log_recording.h"
#include "tests/tools/learned_deploy_support.h"
#include "transport/channels.h"
#include "transport/log_io.h"

namespace birotor {
namespace testing_support {
namespace {

namespace fs = std::filesystem;

// The check flight: 10 s of random steps of the flown vehicle, a manoeuvre
// the learning flight (the scenario's gentle move) did not see.
const std::vector<std::string> kCheckFlight = {"scenario.duration_s=10", "trajectory.kind=random_steps"};

// The shipped config/estimator.yaml with learning switched on, at path.
void WriteLearningConfig(const std::string& path, bool strain_scale, bool body_mass) {
  std::string text = ReadText(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");
  for (const auto& [key, on] : {std::pair<std::string, bool>{"learn_strain_scale: ", strain_scale},
                                std::pair<std::string, bool>{"learn_body_mass: ", body_mass}}) {
    const size_t at = text.find(key + "false");
    ASSERT_NE(at, std::string::npos) << key;
    if (on) text.replace(at + key.size(), 5, "true ");
  }
  std::ofstream(path) << text;
}

double WorseMae(const ScenarioRun& run, int64_t from_utime) {
  return std::max(ForceMae(run, 0, from_utime), ForceMae(run, 1, from_utime));
}

struct Case {
  const char* scenario;
  double learning_flight_s;  // of the scenario's gentle move, learning on
  // The true file: config/estimator.yaml with the flown vehicle's difference.
  void (*make_true)(BirotorParams* vehicle);
  // --learned-max-std-fraction to deploy with, after the default refused
  // (a published sigma above 0.5 x the prior); empty: the default deploys.
  std::string max_std_fraction;
};

// Flies `c` with learning on, deploys its state file into a copy of
// config/estimator.yaml, and returns the worse rotor's MAE (from 1 s) of the
// EKF without learning on the copy, on the true file and on the unchanged
// file, over the check flight.
struct Figures {
  double learned_g[2] = {0, 0};
  double learned_g_std[2] = {0, 0};  // as published
  double mae_updated_n = 0, mae_true_n = 0, mae_unchanged_n = 0;
  int64_t mismatch_updated = 0;  // estimates with MODEL_MISMATCH on the updated file
};

// The EKF without learning on the check flight of c's vehicle: the updated
// file, the true file and the unchanged config/estimator.yaml.
void CheckUpdatedFile(const Case& c, const EstimatorConfig& deployed, Figures* f) {
  const std::string shipped = std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml";
  EstimatorConfig true_file = LoadEstimatorConfig(shipped);
  BirotorParams true_vehicle = BirotorModelOf(true_file.vehicle);
  c.make_true(&true_vehicle);
  true_file.vehicle = BirotorDescription(true_vehicle);
  const Scenario check = LoadScenario(ScenarioFile(c.scenario), kCheckFlight);

  const ScenarioRun with_update = RunScenario(check, deployed);
  const ScenarioRun with_truth = RunScenario(check, true_file);
  const ScenarioRun unchanged = RunScenario(check, LoadEstimatorConfig(shipped));
  const int64_t from = with_update.forces.front().utime + 1000000;
  f->mae_updated_n = WorseMae(with_update, from);
  f->mae_true_n = WorseMae(with_truth, from);
  f->mae_unchanged_n = WorseMae(unchanged, from);
  for (const ForceEstimate& e : with_update.forces) f->mismatch_updated += (e.status & kStatusModelMismatch) ? 1 : 0;
  std::printf("%s: MAE from 1 s: updated %.4f N, true file %.4f N, unchanged %.4f N\n", c.scenario, f->mae_updated_n,
              f->mae_true_n, f->mae_unchanged_n);
}

Figures LearnDeployAndCheck(const Case& c) {
  Figures f;
  Folder folder;
  const std::string shipped = std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml";
  const std::string params = folder.path + "/estimator.yaml", state = folder.path + "/gauge_state";
  const std::string key_file = folder.path + "/site.key", learning_file = folder.path + "/learning.yaml";
  const std::string log = folder.path + "/flight.lcm";
  fs::copy_file(shipped, params);
  const SiteKey key = WriteKeyFile(key_file);
  WriteLearningConfig(learning_file, true, false);

  // 1. Fly with learning on, recorded; persist as the daemon does at a clean stop.
  const EstimatorConfig learning = LoadEstimatorConfig(learning_file);
  const PipelineHealth flown = RecordFlightLog(
      LoadScenario(ScenarioFile(c.scenario), {"scenario.duration_s=" + std::to_string(c.learning_flight_s)}), learning,
      log);
  const GaugeCalibration& learned = flown.gauge;
  EXPECT_TRUE(learned.has_strain_scale);
  const std::string vehicle = VehicleChecksum(BirotorModelOf(learning.vehicle));
  std::string error;
  EXPECT_TRUE(WriteGaugeState(state, learned, vehicle, MessageAuthenticator(key), &error)) << error;

  // 2. Deploy into the copy: gauge_scale[i] = 1 x g_i, every other key kept.
  const std::string before = ReadText(params);
  std::vector<std::string> fraction;
  const std::vector<std::string> deploy_state = {"--update-params", params, "--learned", state, "--site-key", key_file};
  if (!c.max_std_fraction.empty()) {
    EXPECT_NE(RunIdentify(deploy_state), 0);  // not learned by the default
    EXPECT_EQ(ReadText(params), before);
    fraction = {"--learned-max-std-fraction", c.max_std_fraction};
  }
  std::vector<std::string> deploy = deploy_state;
  deploy.insert(deploy.end(), fraction.begin(), fraction.end());
  EXPECT_EQ(RunIdentify(deploy), 0);
  EXPECT_EQ(ReadText(params + ".bak"), before);
  const EstimatorConfig deployed = LoadEstimatorConfig(params);
  EXPECT_FALSE(deployed.ekf.learn_strain_scale);  // the shipped file: no learning
  BirotorParams others = BirotorModelOf(deployed.vehicle);
  for (int i = 0; i < 2; ++i) {
    f.learned_g[i] = learned.strain_scale[i];
    f.learned_g_std[i] = learned.strain_scale_std[i];
    EXPECT_NEAR(deployed.vehicle.arms[i].gauge_scale, learned.strain_scale[i], 1e-9);
    others.gauge_scale[i] = 1.0;
  }
  EXPECT_EQ(VehicleChecksum(others), vehicle);
  // The flight's log (its inputs re-run with the flight's estimator file)
  // deploys the same values: the re-run sees the bytes the estimator saw.
  const std::string log_copy = folder.path + "/from_log.yaml";
  fs::copy_file(shipped, log_copy);
  std::vector<std::string> from_log = {"--update-params",    log_copy,     "--learned", log,
                                       "--estimator-config", learning_file};
  from_log.insert(from_log.end(), fraction.begin(), fraction.end());
  EXPECT_EQ(RunIdentify(from_log), 0);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(LoadEstimatorConfig(log_copy).vehicle.arms[i].gauge_scale, deployed.vehicle.arms[i].gauge_scale, 1e-9);
  }
  // The same state again is refused (the file's vehicle changed): never applied twice.
  const std::string after = ReadText(params);
  EXPECT_NE(RunIdentify(deploy_state), 0);
  EXPECT_EQ(ReadText(params), after);

  // 3. Without learning, on another manoeuvre of that vehicle.
  CheckUpdatedFile(c, deployed, &f);
  std::printf("%s: learned g %.4f +- %.4f / %.4f +- %.4f\n", c.scenario, learned.strain_scale[0],
              learned.strain_scale_std[0], learned.strain_scale[1], learned.strain_scale_std[1]);
  return f;
}

// Gauge 1 reads 0.7 of the file's scale. Measured after 4 s: g 0.6852 +-
// 0.0224 / 1.0025 +- 0.0170 (0.7 and 0.1 published sigmas from the truth;
// before the split after the settling, issue 27: 0.892 +- 0.0095, eleven
// sigmas); updated file 0.0723 N, true file 0.0721 N (1.003), unchanged
// file 5.16 N.
TEST(LearnedDeploy, GaugeScaleMismatch) {
  const Figures f =
      LearnDeployAndCheck({"mismatch_gauge_scale_0p7", 4.0, [](BirotorParams* v) { v->gauge_scale[0] = 0.7; }, ""});
  EXPECT_NEAR(f.learned_g[0], 0.7, 0.022);  // 1.5 x the measured 0.0148
  EXPECT_NEAR(f.learned_g[1], 1.0, 0.02);   // 1.5 x 0.0025, at least the resolution of 0.02
  for (int i = 0; i < 2; ++i) EXPECT_LE(std::abs(f.learned_g[i] - (i == 0 ? 0.7 : 1.0)), 2 * f.learned_g_std[i]);
  EXPECT_LE(f.mae_updated_n, 1.15 * f.mae_true_n);     // the 15 % (measured 1.003)
  EXPECT_GT(f.mae_unchanged_n, 20 * f.mae_updated_n);  // the update is what fixes it (measured 71x)
  EXPECT_EQ(f.mismatch_updated, 0);
}

// Both arms 20 % stiffer (k 3153.6 N m/rad against the file's 2628):
// g_i = k_file / k_true = 0.833 on both. Measured after the whole 15 s:
// g 0.8961 +- 0.0624 / 0.8994 +- 0.0664 (one published sigma off: a
// stiffer arm is not only a smaller static reading, the offsets keep
// 1.2e-4 rad, and the published sigma says so). That sigma is above the
// default --learned-max-std-fraction (0.5 x 0.1): refused by default,
// deployed with 1; updated file 0.0721 N, true file 0.0679 N (1.062),
// unchanged 7.99 N.
TEST(LearnedDeploy, StiffnessMismatch) {
  const Figures f = LearnDeployAndCheck(
      {"mismatch_stiffness_plus20", 15.0, [](BirotorParams* v) { v->arm_stiffness_n_m_rad = 3153.6; }, "1"});
  for (int i = 0; i < 2; ++i) {
    EXPECT_LT(f.learned_g[i], 0.93);  // moves by at least 1/1.5 of the measured 0.104
    EXPECT_LE(std::abs(f.learned_g[i] - 1.0 / 1.2), 2 * f.learned_g_std[i]);
  }
  EXPECT_LE(f.mae_updated_n, 1.15 * f.mae_true_n);     // the 15 % (measured 1.062)
  EXPECT_GT(f.mae_unchanged_n, 20 * f.mae_updated_n);  // measured 111x
  EXPECT_EQ(f.mismatch_updated, 0);
}

// A payload: the body 15 % heavier (4.6 kg against the file's 4.0), learned
// with learn_body_mass (off by default: not usable, docs/mismatch.md) over
// the whole 15 s and deployed from the flight's log (the state file does not
// persist it). Measured: 4.627 +- 0.033 kg (4.616 before the accelerometer
// was fused at its noise's upper bound over its first 50 samples,
// accel_noise_trust_samples: the airborne start's first samples decide how
// much of the payload the offsets take); updated file 0.1387 N, true file
// 0.0742 N (1.87x, before 1.32x: NOT within the 15 %, the 27 g left
// are 0.13 N per rotor through the accelerometer), unchanged 0.381 N. The
// learned mass is inside 1 sigma of the truth. After only 4 s: 4.505 +-
// 0.050 kg and 0.470 N, worse than the unchanged file.
TEST(LearnedDeploy, PayloadBodyMass) {
  const Case c{"mismatch_payload_plus15", 15.0, [](BirotorParams* v) { v->body_mass_kg = 4.6; }, ""};
  Folder folder;
  const std::string params = folder.path + "/estimator.yaml", log = folder.path + "/flight.lcm";
  const std::string learning_file = folder.path + "/learning.yaml";
  fs::copy_file(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml", params);
  WriteLearningConfig(learning_file, false, true);
  const PipelineHealth flown = RecordFlightLog(
      LoadScenario(ScenarioFile(c.scenario), {"scenario.duration_s=" + std::to_string(c.learning_flight_s)}),
      LoadEstimatorConfig(learning_file), log);
  std::printf("learned mass %.4f +- %.4f kg\n", flown.body_mass_kg, flown.body_mass_std_kg);
  EXPECT_NEAR(flown.body_mass_kg, 4.6, 2.0 * flown.body_mass_std_kg);  // measured 0.027 kg off, sigma 0.033
  EXPECT_EQ(RunIdentify({"--update-params", params, "--learned", log, "--estimator-config", learning_file}), 0);
  const EstimatorConfig deployed = LoadEstimatorConfig(params);
  EXPECT_NEAR(deployed.vehicle.body_mass_kg, flown.body_mass_kg, 1e-8);  // 10 digits written
  EXPECT_EQ(deployed.vehicle.arms[0].gauge_scale, 1.0);                  // nothing else deployed
  Figures f;
  CheckUpdatedFile(c, deployed, &f);
  EXPECT_LE(f.mae_updated_n, 2.0 * f.mae_true_n);       // measured 1.87
  EXPECT_LT(f.mae_updated_n, 0.4 * f.mae_unchanged_n);  // measured 0.36
  EXPECT_EQ(f.mismatch_updated, 0);
}

// Issue 37 item 4: the ESTIMATOR_STATUS anyone on the bus can publish,
// claiming gauge scales 1.08 / 0.92 and a 4.3 kg body, tight sigmas, the
// right vehicle checksum.
estimator_status_t ForgedStatus(const std::string& vehicle_checksum) {
  estimator_status_t s{};
  s.method = "ekf";
  s.strain_scale[0] = 1.08;
  s.strain_scale[1] = 0.92;
  s.strain_scale_std[0] = s.strain_scale_std[1] = 0.001;
  s.strain_scale_source = "learned";
  s.body_mass_kg = 4.3;
  s.body_mass_std_kg = 0.01;
  s.body_mass_source = "learned";
  s.vehicle_checksum = vehicle_checksum;
  return s;
}

// The gauge-scale flight (4 s, learning g_i) with the forged status appended
// as its newest. Before issue 37 item 4 this deployed gauge_scale 1.08 /
// 0.92 and body_mass_kg 4.3; now the log's inputs are re-run. Measured: the
// re-run's g 0.6852 +- 0.0224 / 1.0025 +- 0.0170 (as the estimator in
// flight, to 1e-9), deployed; warnings for strain_scale[0] (17.6 combined
// sigmas), strain_scale[1] (4.9) and body_mass_kg (not learned), which stays 4.
TEST(LearnedDeploy, AForgedStatusInTheLogIsNotDeployed) {
  Folder folder;
  const std::string shipped = std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml";
  const std::string params = folder.path + "/estimator.yaml", log = folder.path + "/flight.lcm";
  const std::string learning_file = folder.path + "/learning.yaml";
  fs::copy_file(shipped, params);
  WriteLearningConfig(learning_file, true, false);
  const EstimatorConfig learning = LoadEstimatorConfig(learning_file);
  const estimator_status_t forged = ForgedStatus(VehicleChecksum(BirotorModelOf(learning.vehicle)));
  const PipelineHealth flown = RecordFlightLog(
      LoadScenario(ScenarioFile("mismatch_gauge_scale_0p7"), {"scenario.duration_s=4"}), learning, log, &forged);

  // The shipped estimator file learns the tip mass alone; the flight, with
  // its strain scales learned, learned the tip mass beside them (the arm mode
  // tells a gauge's scale from a tip mass) and recorded it: the re-run's
  // wider sigma holds it, so it is what is deployed: the file's m_p again.
  std::string err;
  ASSERT_EQ(RunIdentify({"--update-params", params, "--learned", log}, &err), 0) << err;
  EXPECT_NEAR(BirotorModelOf(LoadEstimatorConfig(params).vehicle).tip_mass_kg, 0.28812, 0.01);
  fs::remove(params);
  fs::copy_file(shipped, params);

  ASSERT_EQ(RunIdentify({"--update-params", params, "--learned", log, "--estimator-config", learning_file}, &err), 0);
  const BirotorParams deployed = BirotorModelOf(LoadEstimatorConfig(params).vehicle);
  std::printf("forged log: deployed gauge_scale %.4f / %.4f, body_mass_kg %.3f\n", deployed.gauge_scale[0],
              deployed.gauge_scale[1], deployed.body_mass_kg);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(deployed.gauge_scale[i], flown.gauge.strain_scale[i], 1e-9);
  EXPECT_NEAR(deployed.gauge_scale[0], 0.7, 0.022);  // the truth; 1.5 x the measured 0.0148
  EXPECT_NEAR(deployed.gauge_scale[1], 1.0, 0.02);   // 1.5 x 0.0025, at least 0.02
  EXPECT_EQ(deployed.body_mass_kg, BirotorModelOf(learning.vehicle).body_mass_kg);  // 4.0, not 4.3
  EXPECT_NE(err.find("strain_scale[0]: the log's ESTIMATOR_STATUS says 1.08 +- 0.001, its inputs re-run give 0.68"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("strain_scale[1]: the log's ESTIMATOR_STATUS says 0.92 +- 0.001"), std::string::npos) << err;
  EXPECT_NE(err.find("body_mass_kg: the log's ESTIMATOR_STATUS says 4.3 +- 0.01, but the re-run of its inputs did "
                     "not learn it: the recorded status was not used"),
            std::string::npos)
      << err;
}

// A log with nothing but the forged status, and one too short to learn in.
TEST(LearnedDeploy, ALogWhoseInputsSupportNoValueDeploysNothing) {
  Folder folder;
  const std::string params = folder.path + "/estimator.yaml", log = folder.path + "/status_only.lcm";
  const std::string learning_file = folder.path + "/learning.yaml";
  fs::copy_file(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml", params);
  WriteLearningConfig(learning_file, true, true);
  LogWriter writer;
  std::string error, err;
  ASSERT_TRUE(writer.Open(log, &error)) << error;
  const BirotorParams vehicle = BirotorModelOf(LoadEstimatorConfig(params).vehicle);
  ASSERT_TRUE(writer.WriteMessage(MakeChannelNames().estimator_status, 1, ForgedStatus(VehicleChecksum(vehicle))));
  ASSERT_TRUE(writer.Close()) << writer.error();
  const std::string before = ReadText(params);
  EXPECT_NE(RunIdentify({"--update-params", params, "--learned", log, "--estimator-config", learning_file}, &err), 0);
  EXPECT_NE(err.find(log + ": its inputs cannot support a learned value (0 FORCE estimates from BIROTOR_STRAIN, 0 "
                           "BIROTOR_MOTOR samples): nothing written"),
            std::string::npos)
      << err;
  EXPECT_EQ(ReadText(params), before);

  // 0.5 s of the gauge-scale flight: too short to have learned.
  const std::string short_log = folder.path + "/short.lcm";
  RecordFlightLog(LoadScenario(ScenarioFile("mismatch_gauge_scale_0p7"), {"scenario.duration_s=0.5"}),
                  LoadEstimatorConfig(learning_file), short_log);
  EXPECT_EQ(RunIdentify({"--update-params", params, "--learned", short_log, "--estimator-config", learning_file}, &err),
            1);
  // Measured: g_1 0.969 +- 0.170 after 0.5 s.
  EXPECT_NE(err.find("short.lcm: strain_scale of arm 1 0.96"), std::string::npos) << err;
  EXPECT_NE(err.find("was not learned (sigma not below 0.5 x the prior sigma 0.1 = 0.05"), std::string::npos) << err;
  EXPECT_EQ(ReadText(params), before);
}

// A state file counts only under the site key: one signed with another key
// (forged) or without a mac line is refused with its reason, nothing
// written; the same values signed with the site key are deployed.
TEST(LearnedDeploy, AStateFileIsDeployedOnlyUnderTheSiteKey) {
  Folder folder;
  const std::string params = folder.path + "/estimator.yaml", key_file = folder.path + "/site.key";
  fs::copy_file(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml", params);
  const SiteKey key = WriteKeyFile(key_file);
  const SiteKey other = WriteKeyFile(folder.path + "/other.key");
  const std::string vehicle = VehicleChecksum(BirotorModelOf(LoadEstimatorConfig(params).vehicle));
  GaugeCalibration claimed;
  claimed.has_strain_scale = true;
  claimed.strain_scale[0] = 1.08;
  claimed.strain_scale[1] = 0.92;
  claimed.strain_scale_std[0] = claimed.strain_scale_std[1] = 0.001;
  claimed.offset_std_rad[0] = claimed.offset_std_rad[1] = 1.8e-5;
  const std::string forged = folder.path + "/forged_state", unsigned_state = folder.path + "/unsigned_state";
  const std::string genuine = folder.path + "/gauge_state";
  std::string error, err;
  ASSERT_TRUE(WriteGaugeState(forged, claimed, vehicle, MessageAuthenticator(other), &error)) << error;
  ASSERT_TRUE(WriteGaugeState(unsigned_state, claimed, vehicle, &error)) << error;
  ASSERT_TRUE(WriteGaugeState(genuine, claimed, vehicle, MessageAuthenticator(key), &error)) << error;
  const std::string before = ReadText(params);
  EXPECT_EQ(RunIdentify({"--update-params", params, "--learned", forged, "--site-key", key_file}, &err), 1);
  EXPECT_NE(err.find("--learned " + forged +
                     ": not authenticated (mac does not verify under the site key: forged, altered or another key): "
                     "not deployed, nothing written"),
            std::string::npos)
      << err;
  EXPECT_EQ(RunIdentify({"--update-params", params, "--learned", unsigned_state, "--site-key", key_file}, &err), 1);
  EXPECT_NE(err.find(unsigned_state + ": not authenticated (no mac line"), std::string::npos) << err;
  // No readable key: the estimator's wording, nothing deployed.
  EXPECT_EQ(
      RunIdentify({"--update-params", params, "--learned", genuine, "--site-key", folder.path + "/absent.key"}, &err),
      1);
  EXPECT_NE(err.find("gauge state file " + genuine + " is not authenticated ("), std::string::npos) << err;
  EXPECT_EQ(ReadText(params), before);
  EXPECT_EQ(RunIdentify({"--update-params", params, "--learned", genuine, "--site-key", key_file}), 0);
  const BirotorParams deployed = BirotorModelOf(LoadEstimatorConfig(params).vehicle);
  EXPECT_EQ(deployed.gauge_scale[0], 1.08);  // 1 x g, 10 digits written
  EXPECT_EQ(deployed.gauge_scale[1], 0.92);
}

}  // namespace
}  // namespace testing_support
}  // namespace birotor
