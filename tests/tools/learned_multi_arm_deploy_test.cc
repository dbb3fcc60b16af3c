// Issue 36 item 4 for a vehicle with N arms: the gauge state file of
// `birotor-estimator --vehicle config/vehicles/trirotor.yaml` (nodes/
// vehicle_state_file.h, signed under a test site key) deployed with
// `birotor-identify --vehicle DESC --update-params COPY --learned STATE` (and
// without --vehicle, the N-arm form detected in the file): every arm's
// tip_mass_kg x the learned ratio r, the copy reloads and its description
// checksum changes; a forged, unsigned, foreign, other-arm-count or
// not-learned state file is refused with one line and the file untouched;
// the birotor's --update-params path is unchanged.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "estimator/multi_arm_pipeline.h"
#include "model/vehicle_description_checksum.h"
#include "nodes/gauge_state_file.h"
#include "nodes/state_file_common.h"
#include "nodes/vehicle_state_file.h"
#include "params/estimator_config_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "params/vehicle_section_update.h"
#include "security/message_authenticator.h"
#include "simulator/multi_arm_simulator.h"
#include "tests/estimator/multi_arm_source_files.h"
#include "tests/tools/learned_deploy_support.h"

namespace birotor {
namespace testing_support {
namespace {

const std::string kTrirotor = std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml";
constexpr double kFileTipMassKg = 0.28812;  // every arm of config/vehicles/trirotor.yaml

// What a trirotor daemon persists after a flight that learned r (offsets as
// tests/nodes/vehicle_state_file_test.cc's).
MultiArmGaugeState Learned(double ratio, double ratio_std) {
  MultiArmGaugeState state;
  state.arm_count = 3;
  state.offset_rad = {1.4937e-5, -1.0123e-5, 2.25e-6, 0, 0, 0};
  state.offset_std_rad = {1.1e-6, 1.2e-6, 9.5e-7, 0, 0, 0};
  state.has_tip_mass = true;
  state.tip_mass_ratio = ratio;
  state.tip_mass_ratio_std = ratio_std;
  return state;
}

// The N-arm pipeline on 8 s of the trirotor's gentle flight with every tip
// mass 10 % above the description's (tests/nodes/
// multi_arm_tip_mass_resume_test.cc's flight), tip-mass learning on; the
// state the daemon persists at its clean stop.
class PipelineSink : public SampleSink {
 public:
  explicit PipelineSink(MultiArmPipeline* pipeline) : pipeline_(pipeline) {}
  void OnStrainN(const MultiArmStrainSample& s) override {
    MultiArmForceEstimate estimate;
    pipeline_->OnStrain(s, &estimate);
  }
  void OnMotorN(const MultiArmMotorSample& s) override { pipeline_->OnMotor(s); }
  void OnImu(const ImuSample& s) override { pipeline_->OnImu(s); }

 private:
  MultiArmPipeline* pipeline_;
};

MultiArmGaugeState FlyTipMassesTenPercentHeavier() {
  EstimatorConfig config = Config();
  config.vehicle = LoadVehicleDescription(kTrirotor);
  config.model_consistency.arm_mode_learn_tip_mass = true;
  VehicleDescription flown = config.vehicle;
  for (int i = 0; i < flown.arm_count; ++i) flown.arms[static_cast<size_t>(i)].tip_mass_kg *= 1.1;
  const Scenario gentle =
      ScenarioFor("gentle", {"scenario.duration_s=8", "scenario.seed=1", "gauge.offset_rad=[0, 0, 0]"}, 3);
  MultiArmPipeline pipeline(config);
  PipelineSink sink(&pipeline);
  MultiArmSimulator simulator(flown, gentle);
  simulator.Run(&sink);
  return pipeline.GaugeState();
}

class LearnedMultiArmDeploy : public ::testing::Test {
 protected:
  void SetUp() override {
    copy_ = folder_.path + "/tri.yaml";
    state_ = folder_.path + "/gauge_state_n";
    key_file_ = folder_.path + "/site.key";
    std::filesystem::copy_file(kTrirotor, copy_);
    authenticator_ = std::make_unique<MessageAuthenticator>(WriteKeyFile(key_file_));
    checksum_ = DescriptionChecksum(LoadVehicleDescription(kTrirotor));
    original_ = ReadText(copy_);
  }
  void WriteState(const MultiArmGaugeState& state, const std::string& checksum) {
    std::string error;
    ASSERT_TRUE(WriteVehicleGaugeState(state_, state, checksum, *authenticator_, &error)) << error;
  }
  // birotor-identify --vehicle trirotor.yaml --update-params COPY --learned STATE --site-key KEY [more].
  int Deploy(std::string* err, const std::vector<std::string>& more = {}) {
    std::vector<std::string> args = {"--vehicle", kTrirotor, "--update-params", copy_,
                                     "--learned", state_,    "--site-key",      key_file_};
    args.insert(args.end(), more.begin(), more.end());
    return RunIdentify(args, err);
  }
  // A refusal: exit 1, one line naming the state file (or the copy), the copy and no backup written.
  void ExpectRefused(const std::string& reason, const std::vector<std::string>& more = {}) {
    std::string err;
    EXPECT_EQ(Deploy(&err, more), 1);
    EXPECT_NE(err.find(reason), std::string::npos) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_EQ(ReadText(copy_), original_);
    EXPECT_FALSE(std::filesystem::exists(copy_ + ".bak"));
  }

  Folder folder_;
  std::string copy_, state_, key_file_, checksum_, original_;
  std::unique_ptr<MessageAuthenticator> authenticator_;
};

TEST_F(LearnedMultiArmDeploy, ASignedRatioScalesEveryTipMassAndTheFileReloads) {
  WriteState(Learned(1.09, 0.01), checksum_);
  std::string err;
  ASSERT_EQ(Deploy(&err), 0) << err;
  const VehicleDescription before = LoadVehicleDescription(kTrirotor);
  VehicleDescription after = LoadVehicleDescription(copy_);  // reloads: plausible, complete
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(after.arms[i].tip_mass_kg, 1.09 * kFileTipMassKg, 1e-9) << i;  // 0.3140508 kg
    // The offsets are not deployed (as the birotor's): the description's 0 stays.
    EXPECT_EQ(after.arms[i].gauge_offset_rad, 0.0) << i;
  }
  EXPECT_NE(DescriptionChecksum(after), checksum_);
  for (size_t i = 0; i < 3; ++i) after.arms[i].tip_mass_kg = kFileTipMassKg;
  EXPECT_EQ(FirstDifference(after, before), "");  // nothing else changed
  EXPECT_EQ(ReadText(copy_ + ".bak"), original_);
  EXPECT_NE(ReadIdentificationStamp(copy_).find(
                "arms[0].tip_mass_kg 0.28812 -> 0.314051 (learned 1.09 +- 0.01); arms[1].tip_mass_kg"),
            std::string::npos)
      << ReadIdentificationStamp(copy_);
  // The same state file again: its vehicle is no longer this description's.
  const std::string deployed = ReadText(copy_);
  std::filesystem::remove(copy_ + ".bak");
  EXPECT_EQ(RunIdentify({"--update-params", copy_, "--learned", state_, "--site-key", key_file_}, &err), 1);
  EXPECT_NE(err.find(state_ + ": written for another vehicle description"), std::string::npos) << err;
  EXPECT_EQ(ReadText(copy_), deployed);
}

// End to end: what a flight of the 10 % heavier vehicle learned, deployed.
TEST_F(LearnedMultiArmDeploy, AFlightsLearnedRatioIsDeployed) {
  const MultiArmGaugeState flown = FlyTipMassesTenPercentHeavier();
  ASSERT_TRUE(flown.has_tip_mass);
  WriteState(flown, checksum_);
  std::string err;
  ASSERT_EQ(Deploy(&err), 0) << err;
  const VehicleDescription after = LoadVehicleDescription(copy_);
  std::printf("learned r %.6f +- %.6f; deployed tip masses %.6f %.6f %.6f kg (true %.6f)\n", flown.tip_mass_ratio,
              flown.tip_mass_ratio_std, after.arms[0].tip_mass_kg, after.arms[1].tip_mass_kg, after.arms[2].tip_mass_kg,
              1.1 * kFileTipMassKg);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(after.arms[i].tip_mass_kg, flown.tip_mass_ratio * kFileTipMassKg, 1e-9) << i;
    // As the resume test's bound on r: 3 sigma + 0.02 of the truth 1.1.
    // Measured r 1.090112 +- 0.013638 (0.72 sigma low): 0.314083 kg per arm, true 0.316932.
    EXPECT_NEAR(after.arms[i].tip_mass_kg, 1.1 * kFileTipMassKg,
                (3.0 * flown.tip_mass_ratio_std + 0.02) * kFileTipMassKg)
        << i;
  }
}

TEST_F(LearnedMultiArmDeploy, WithoutVehicleTheNArmFormIsDetectedAndALinkIsUpdatedThroughItsTarget) {
  WriteState(Learned(1.09, 0.01), checksum_);
  const std::string link = folder_.path + "/link.yaml";
  std::filesystem::create_symlink(copy_, link);
  std::string err;
  ASSERT_EQ(RunIdentify({"--update-params", link, "--learned", state_, "--site-key", key_file_}, &err), 0) << err;
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_NEAR(LoadVehicleDescription(link).arms[2].tip_mass_kg, 1.09 * kFileTipMassKg, 1e-9);
  EXPECT_EQ(ReadText(copy_ + ".bak"), original_);
}

TEST_F(LearnedMultiArmDeploy, AnUnsignedOrForgedFileIsRefused) {
  const std::string text = VehicleStateText(Learned(1.09, 0.01), checksum_);
  std::ofstream(state_) << text;  // no mac line
  ExpectRefused("--learned " + state_ + ": not authenticated (no mac line");
  // A forged ratio: its checksum recomputed, the genuine mac kept.
  const std::string mac = StateFileMacLine(text, *authenticator_);
  std::ofstream(state_) << VehicleStateText(Learned(1.5, 0.01), checksum_) + mac;
  ExpectRefused("--learned " + state_ + ": not authenticated (mac does not verify");
  // Signed under another key.
  std::ofstream(state_) << text + StateFileMacLine(text, MessageAuthenticator(SiteKey(SiteKey::Bytes{})));
  ExpectRefused("not authenticated (mac does not verify");
  // No readable site key.
  WriteState(Learned(1.09, 0.01), checksum_);
  std::string err;
  EXPECT_EQ(RunIdentify({"--vehicle", kTrirotor, "--update-params", copy_, "--learned", state_, "--site-key",
                         folder_.path + "/absent.key"},
                        &err),
            1);
  EXPECT_NE(err.find("--learned: gauge state file " + state_ + " is not authenticated"), std::string::npos) << err;
  EXPECT_EQ(ReadText(copy_), original_);
}

TEST_F(LearnedMultiArmDeploy, AnotherVehicleOrArmCountIsRefused) {
  VehicleDescription other = LoadVehicleDescription(kTrirotor);
  other.body_mass_kg = 4.1;
  WriteState(Learned(1.09, 0.01), DescriptionChecksum(other));
  ExpectRefused(state_ + ": written for another vehicle description (vehicle checksum " + DescriptionChecksum(other) +
                ", expected " + checksum_ + "): not deployed, nothing written");
  // This description's checksum, signed, but two arms.
  MultiArmGaugeState two = Learned(1.09, 0.01);
  two.arm_count = 2;
  const std::string text = VehicleStateText(two, checksum_);
  std::ofstream(state_) << text + StateFileMacLine(text, *authenticator_);
  ExpectRefused(state_ + ": arm_count 2, the description has 3: refused: not deployed, nothing written");
  // --vehicle names another description than the file holds.
  const std::string heavier = folder_.path + "/heavier.yaml";
  std::string updated, error;
  ASSERT_TRUE(UpdateDescriptionArmValues(original_, "tip_mass_kg", {0.3, 0.3, 0.3}, "", &updated, &error)) << error;
  std::ofstream(heavier) << updated;
  WriteState(Learned(1.09, 0.01), checksum_);
  std::string err;
  EXPECT_EQ(
      RunIdentify({"--vehicle", heavier, "--update-params", copy_, "--learned", state_, "--site-key", key_file_}, &err),
      1);
  EXPECT_NE(err.find("--update-params " + copy_ + " does not hold the description of --vehicle " + heavier),
            std::string::npos)
      << err;
  EXPECT_EQ(ReadText(copy_), original_);
}

TEST_F(LearnedMultiArmDeploy, ASigmaAboveTheFractionOrNoLearnedRatioIsRefused) {
  // 0.08 is not below 0.5 x 0.15 (arm_mode_unconfirmed_tip_mass_std).
  WriteState(Learned(1.09, 0.08), checksum_);
  ExpectRefused(state_ +
                ": tip_mass_ratio 1.09 +- 0.08 was not learned (sigma not below 0.5 x the prior sigma 0.15 = " +
                "0.075, --learned-max-std-fraction; fly longer in free flight): " + copy_ +
                " vehicle.arms[*].tip_mass_kg not updated");
  std::string err;
  ASSERT_EQ(Deploy(&err, {"--learned-max-std-fraction", "0.6"}), 0) << err;  // 0.09: learned
  EXPECT_NEAR(LoadVehicleDescription(copy_).arms[1].tip_mass_kg, 1.09 * kFileTipMassKg, 1e-9);
  std::filesystem::copy_file(kTrirotor, copy_, std::filesystem::copy_options::overwrite_existing);
  std::filesystem::remove(copy_ + ".bak");
  MultiArmGaugeState offsets_only = Learned(1.09, 0.01);
  offsets_only.has_tip_mass = false;
  WriteState(offsets_only, checksum_);
  ExpectRefused(state_ + ": holds no learned tip mass");
}

// A description in the birotor form flown by the N-arm daemon (--vehicle, N = 2): r goes into its one tip_mass_kg.
TEST_F(LearnedMultiArmDeploy, ABirotorFormDescriptionTakesRInItsOneTipMass) {
  const std::string reference = folder_.path + "/reference_vehicle.yaml";
  std::filesystem::copy_file(std::string(BIROTOR_SOURCE_DIR) + "/config/reference_vehicle.yaml", reference);
  MultiArmGaugeState two = Learned(1.09, 0.01);
  two.arm_count = 2;
  WriteState(two, DescriptionChecksum(LoadVehicleDescription(reference)));
  std::string err;
  ASSERT_EQ(
      RunIdentify({"--vehicle", reference, "--update-params", reference, "--learned", state_, "--site-key", key_file_},
                  &err),
      0)
      << err;
  const BirotorParams after = BirotorModelOf(LoadVehicleDescription(reference));
  EXPECT_NEAR(after.tip_mass_kg, 1.09 * kFileTipMassKg, 1e-9);
  EXPECT_NE(ReadText(reference).find("  tip_mass_kg: 0.3140508         # m_p, lumped"), std::string::npos);
}

TEST_F(LearnedMultiArmDeploy, TheBirotorsParameterFileWorksAsBefore) {
  const std::string params = folder_.path + "/estimator.yaml";
  std::filesystem::copy_file(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml", params);
  const BirotorParams vehicle = BirotorModelOf(LoadEstimatorConfig(params).vehicle);
  GaugeCalibration state = GaugeCalibration::FromVehicle(vehicle);
  state.has_tip_mass = true;
  state.tip_mass_kg = 0.31;
  state.tip_mass_std_kg = 0.003;
  std::string error, err;
  // The N-arm state file is not the birotor's: refused by its kind.
  WriteState(Learned(1.09, 0.01), checksum_);
  EXPECT_EQ(RunIdentify({"--update-params", params, "--learned", state_, "--site-key", key_file_}, &err), 1);
  EXPECT_NE(err.find("gauge state file of a vehicle with N arms"), std::string::npos) << err;
  const std::string birotor_state = folder_.path + "/gauge_state";
  ASSERT_TRUE(WriteGaugeState(birotor_state, state, VehicleChecksum(vehicle), *authenticator_, &error)) << error;
  ASSERT_EQ(RunIdentify({"--update-params", params, "--learned", birotor_state, "--site-key", key_file_}, &err), 0)
      << err;
  const EstimatorConfig deployed = LoadEstimatorConfig(params);
  for (size_t i = 0; i < 2; ++i) EXPECT_NEAR(deployed.vehicle.arms[i].tip_mass_kg, 0.31, 1e-12);
}

}  // namespace
}  // namespace testing_support
}  // namespace birotor
