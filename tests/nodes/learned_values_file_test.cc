// What `birotor-identify --learned FILE` reads (nodes/learned_values_file.h):
// a gauge state file's strain scales only under a verifying mac, the newest
// learned ESTIMATOR_STATUS of a flight log as recorded (for comparison), the
// refusals (forged, unsigned, another vehicle, neither kind of file), and the
// 3-combined-sigma comparison. The values are arbitrary test numbers,
// compared exactly.
#include "nodes/learned_values_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include "nodes/gauge_state_file.h"
#include "nodes/status_message.h"
#include "security/site_key.h"
#include "transport/channels.h"
#include "transport/log_io.h"

namespace birotor {
namespace {

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "/" + name + "_" + std::to_string(getpid());
}

const std::string kVehicle = VehicleChecksum(BirotorParams());

SiteKey TestSiteKey(uint8_t fill) {
  SiteKey::Bytes bytes;
  bytes.fill(fill);
  return SiteKey(bytes);
}

GaugeCalibration LearnedCalibration() {
  GaugeCalibration calibration;
  calibration.has_strain_scale = true;
  calibration.strain_scale[0] = 0.8924;
  calibration.strain_scale[1] = 0.9938;
  calibration.strain_scale_std[0] = 0.0095;
  calibration.strain_scale_std[1] = 0.0094;
  calibration.offset_rad[0] = 3.6e-4;  // above any tare bound: not deployed, not checked
  calibration.offset_std_rad[0] = calibration.offset_std_rad[1] = 1.8e-5;
  calibration.has_tip_mass = true;
  calibration.tip_mass_kg = 0.3434;
  calibration.tip_mass_std_kg = 0.0032;
  return calibration;
}

TEST(LearnedValuesFileTest, AStateFileUnderTheSiteKeyGivesItsStrainScales) {
  const std::string path = TempPath("learned_state");
  const MessageAuthenticator authenticator(TestSiteKey(0x11));
  std::string error;
  ASSERT_TRUE(WriteGaugeState(path, LearnedCalibration(), kVehicle, authenticator, &error)) << error;
  LearnedVehicleValues learned;
  ASSERT_TRUE(ReadLearnedState(path, kVehicle, authenticator, &learned, &error)) << error;
  EXPECT_TRUE(learned.has_strain_scale);
  EXPECT_FALSE(learned.has_body_mass);  // not persisted
  EXPECT_EQ(learned.strain_scale[0], 0.8924);
  EXPECT_EQ(learned.strain_scale_std[1], 0.0094);
  EXPECT_TRUE(learned.has_tip_mass);
  EXPECT_EQ(learned.tip_mass_kg, 0.3434);
  EXPECT_EQ(learned.tip_mass_std_kg, 0.0032);
  // Another vehicle (e.g. the file already updated with this state): refused.
  BirotorParams other;
  other.gauge_scale[0] = 0.8924;
  EXPECT_FALSE(ReadLearnedState(path, VehicleChecksum(other), authenticator, &learned, &error));
  EXPECT_NE(error.find("written for another vehicle"), std::string::npos) << error;
  std::remove(path.c_str());
}

TEST(LearnedValuesFileTest, AForgedOrUnsignedStateFileIsRefused) {
  const std::string forged = TempPath("learned_forged"), unsigned_file = TempPath("learned_unsigned");
  const MessageAuthenticator site(TestSiteKey(0x11));
  std::string error;
  ASSERT_TRUE(WriteGaugeState(forged, LearnedCalibration(), kVehicle, MessageAuthenticator(TestSiteKey(0x22)), &error));
  ASSERT_TRUE(WriteGaugeState(unsigned_file, LearnedCalibration(), kVehicle, &error)) << error;
  LearnedVehicleValues learned;
  learned.strain_scale[0] = 1.5;  // untouched by a refusal
  EXPECT_FALSE(ReadLearnedState(forged, kVehicle, site, &learned, &error));
  EXPECT_EQ(error,
            forged + ": not authenticated (mac does not verify under the site key: forged, altered or another key)");
  EXPECT_FALSE(ReadLearnedState(unsigned_file, kVehicle, site, &learned, &error));
  EXPECT_EQ(error, unsigned_file + ": not authenticated (no mac line; written without the site key or forged)");
  EXPECT_EQ(learned.strain_scale[0], 1.5);
  std::remove(forged.c_str());
  std::remove(unsigned_file.c_str());
}

estimator_status_t Status(const char* scale_source, double g1, const char* mass_source, double mass_kg) {
  estimator_status_t s{};
  s.method = "ekf";
  s.strain_scale[0] = g1;
  s.strain_scale[1] = 1.0;
  s.strain_scale_std[0] = s.strain_scale_std[1] = 0.01;
  s.strain_scale_source = scale_source;
  s.body_mass_kg = mass_kg;
  s.body_mass_std_kg = 0.02;
  s.body_mass_source = mass_source;
  s.vehicle_checksum = kVehicle;
  return s;
}

// A log of the flight: learning, then a restart without it (params only).
std::string WriteFlightLog(const std::string& name, const std::string& checksum) {
  const std::string path = TempPath(name) + ".lcm";
  const ChannelNames channels = MakeChannelNames("BIROTOR_");
  LogWriter writer;
  std::string error;
  EXPECT_TRUE(writer.Open(path, &error)) << error;
  estimator_status_t early = Status("learned", 0.95, "learned", 4.3);
  estimator_status_t newest = Status("state_file", 0.90, "learned", 4.6);
  newest.vehicle_checksum = checksum;
  const estimator_status_t other_prefix = Status("learned", 0.5, "learned", 9.0);
  const estimator_status_t not_learned = Status("params", 1.0, "params", 4.0);
  writer.WriteMessage(channels.estimator_status, 1, early);
  writer.WriteMessage(channels.estimator_status, 2, newest);
  writer.WriteMessage("OTHER_ESTIMATOR_STATUS", 3, other_prefix);
  writer.WriteMessage(channels.estimator_status, 4, not_learned);
  EXPECT_TRUE(writer.Close()) << writer.error();
  return path;
}

TEST(LearnedValuesFileTest, AFlightLogGivesItsNewestRecordedLearnedStatus) {
  const std::string path = WriteFlightLog("learned_log", "0000000000000000");
  EXPECT_TRUE(IsLcmLog(path));
  LearnedVehicleValues recorded;
  std::string checksum, error;
  ASSERT_TRUE(ReadRecordedLearnedValues(path, "BIROTOR_", &recorded, &checksum, &error)) << error;
  EXPECT_EQ(checksum, "0000000000000000");
  EXPECT_TRUE(recorded.has_strain_scale);
  EXPECT_EQ(recorded.strain_scale[0], 0.90);
  EXPECT_TRUE(recorded.has_body_mass);
  EXPECT_EQ(recorded.body_mass_kg, 4.6);
  EXPECT_EQ(recorded.body_mass_std_kg, 0.02);
  // On another prefix there is no learned status.
  EXPECT_FALSE(ReadRecordedLearnedValues(path, "NONE_", &recorded, &checksum, &error));
  EXPECT_NE(error.find("no NONE_ESTIMATOR_STATUS message with a learned value"), std::string::npos) << error;
  std::remove(path.c_str());
}

TEST(LearnedValuesFileTest, NeitherKindOfFileIsRefused) {
  const std::string path = TempPath("learned_neither");
  std::ofstream(path) << "vehicle:\n  body_mass_kg: 4.0\n";
  EXPECT_FALSE(IsLcmLog(path));
  LearnedVehicleValues learned;
  std::string error;
  EXPECT_FALSE(ReadLearnedState(path, kVehicle, MessageAuthenticator(TestSiteKey(0x11)), &learned, &error));
  EXPECT_NE(error.find("not a gauge state file"), std::string::npos) << error;
  EXPECT_NE(error.find("nor an LCM log"), std::string::npos) << error;
  std::remove(path.c_str());
}

// The forged status of issue 37 item 4 against a re-run: g 0.6852 +- 0.0224
// / 1.0025 +- 0.0170 (the learned_deploy_test gauge-scale flight), no mass.
TEST(LearnedValuesFileTest, RecordedValuesMoreThanThreeCombinedSigmasOffAreReported) {
  LearnedVehicleValues recorded, rerun;
  recorded.has_strain_scale = recorded.has_body_mass = true;
  recorded.strain_scale[0] = 1.08;
  recorded.strain_scale[1] = 0.92;
  recorded.strain_scale_std[0] = recorded.strain_scale_std[1] = 0.001;
  recorded.body_mass_kg = 4.3;
  recorded.body_mass_std_kg = 0.01;
  rerun.has_strain_scale = true;
  rerun.strain_scale[0] = 0.6852;
  rerun.strain_scale_std[0] = 0.0224;
  rerun.strain_scale[1] = 1.0025;
  rerun.strain_scale_std[1] = 0.0170;
  const std::vector<LearnedDisagreement> d = CompareLearnedValues(recorded, rerun);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d[0].field, "strain_scale[0]");
  EXPECT_NEAR(d[0].sigmas, (1.08 - 0.6852) / std::hypot(0.001, 0.0224), 1e-9);  // 17.6
  EXPECT_EQ(d[1].field, "strain_scale[1]");
  EXPECT_NEAR(d[1].sigmas, (1.0025 - 0.92) / std::hypot(0.001, 0.0170), 1e-9);  // 4.8
  EXPECT_EQ(d[2].field, "body_mass_kg");
  EXPECT_FALSE(d[2].rerun_learned);
  EXPECT_EQ(DisagreementText(d[0]),
            "strain_scale[0]: the log's ESTIMATOR_STATUS says 1.08 +- 0.001, its inputs re-run give 0.6852 +- 0.0224 "
            "(17.6 combined sigmas apart): the recorded status was not used");
  EXPECT_EQ(DisagreementText(d[2]),
            "body_mass_kg: the log's ESTIMATOR_STATUS says 4.3 +- 0.01, but the re-run of its inputs did not learn "
            "it: the recorded status was not used");
  // Within 3 combined sigmas (2.9): no report.
  recorded.has_body_mass = false;
  recorded.strain_scale[0] = 0.6852 + 2.9 * std::hypot(0.001, 0.0224);
  recorded.strain_scale[1] = 1.0025;
  EXPECT_TRUE(CompareLearnedValues(recorded, rerun).empty());
}

}  // namespace
}  // namespace birotor
