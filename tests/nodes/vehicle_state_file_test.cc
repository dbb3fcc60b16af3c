// The gauge state file of a vehicle with N arms (nodes/vehicle_state_file.h)
// on the trirotor's description: round trip, refusal of a corrupt, foreign,
// forged or out-of-range file with the field named, the birotor's state file
// and this one never taken for each other nor overwritten by the other
// daemon, and a path that is not a state file never replaced.
#include "nodes/vehicle_state_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "nodes/gauge_state_file.h"
#include "nodes/state_file_common.h"
#include "params/vehicle_description_yaml.h"
#include "program/logging.h"
#include "security/site_key.h"
#include "tests/nodes/state_file_test_files.h"

namespace birotor {
namespace {

constexpr double kMaxOffsetRad = 5e-4;  // tare.max_offset_rad of config/estimator.yaml

VehicleDescription Trirotor() {
  return LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml");
}

// What a trirotor daemon persists after a flight that learned r = 1.1.
MultiArmGaugeState Learned() {
  MultiArmGaugeState state;
  state.arm_count = 3;
  state.offset_rad = {1.4937e-5, -1.0123e-5, 2.25e-6, 0, 0, 0};
  state.offset_std_rad = {1.1e-6, 1.2e-6, 9.5e-7, 0, 0, 0};
  state.has_tip_mass = true;
  state.tip_mass_ratio = 1.0987654321;
  state.tip_mass_ratio_std = 0.0123;
  return state;
}

// text signed as the daemon signs it: a forger holding the key, or a test
// that must get past the mac to reach a later check.
void SpitSigned(const std::string& path, const std::string& text, const MessageAuthenticator& key) {
  Spit(path, text + StateFileMacLine(text, key));
}

TEST(VehicleStateFileTest, RoundTripKeepsEveryBit) {
  const std::string path = TempStatePath("vehicle_round_trip");
  const MessageAuthenticator key = SiteKeyOfByte(0x5a);
  const std::string vehicle = VehicleStateChecksum(Trirotor());
  std::string error;
  ASSERT_TRUE(WriteVehicleGaugeState(path, Learned(), vehicle, key, &error)) << error;
  const std::string text = Slurp(path);
  EXPECT_EQ(text.rfind("# birotor-estimator gauge offset state, N arms\nvehicle_checksum: " + vehicle +
                           "\narm_count: 3\ngauge_offset_rad: ",
                       0),
            0u)
      << text;
  EXPECT_NE(text.find("\ntip_mass_ratio: 1.0987654321\n"), std::string::npos) << text;
  MultiArmGaugeState read;
  ASSERT_TRUE(ReadVehicleGaugeState(path, vehicle, 3, kMaxOffsetRad, key, &read, &error)) << error;
  EXPECT_EQ(read.arm_count, 3);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(read.offset_rad[i], Learned().offset_rad[i]) << i;
    EXPECT_EQ(read.offset_std_rad[i], Learned().offset_std_rad[i]) << i;
  }
  EXPECT_TRUE(read.has_tip_mass);
  EXPECT_EQ(read.tip_mass_ratio, Learned().tip_mass_ratio);
  EXPECT_EQ(read.tip_mass_ratio_std, Learned().tip_mass_ratio_std);
  EXPECT_EQ(read.source, GaugeOffsetSource::kStateFile);
  // Without a learned tip mass: no tip-mass lines, none read back.
  MultiArmGaugeState offsets_only = Learned();
  offsets_only.has_tip_mass = false;
  ASSERT_TRUE(WriteVehicleGaugeState(path, offsets_only, vehicle, key, &error)) << error;
  EXPECT_EQ(Slurp(path).find("tip_mass"), std::string::npos);
  ASSERT_TRUE(ReadVehicleGaugeState(path, vehicle, 3, kMaxOffsetRad, key, &read, &error)) << error;
  EXPECT_FALSE(read.has_tip_mass);
  std::remove(path.c_str());
}

TEST(VehicleStateFileTest, ACorruptFileIsRefused) {
  const std::string path = TempStatePath("vehicle_corrupt");
  const MessageAuthenticator key = SiteKeyOfByte(0x5a);
  const std::string vehicle = VehicleStateChecksum(Trirotor());
  std::string text = VehicleStateText(Learned(), vehicle);
  text[text.find("arm_count: 3") - 2] ^= 1;  // a digit of the vehicle checksum line's end
  SpitSigned(path, text, key);
  MultiArmGaugeState read;
  std::string error;
  EXPECT_FALSE(ReadVehicleGaugeState(path, vehicle, 3, kMaxOffsetRad, key, &read, &error));
  EXPECT_EQ(error, path + ": corrupt (checksum mismatch)");
  EXPECT_EQ(read.arm_count, 0);  // unchanged
  // A missing field, checksum and mac right.
  std::string body = VehicleStateText(Learned(), vehicle);
  body = body.substr(0, body.find("gauge_offset_std_rad"));
  SpitSigned(path, body + "checksum: " + TextChecksum(body) + "\n", key);
  EXPECT_FALSE(ReadVehicleGaugeState(path, vehicle, 3, kMaxOffsetRad, key, &read, &error));
  EXPECT_NE(error.find("corrupt (gauge_offset_rad or gauge_offset_std_rad missing or not 3 finite numbers)"),
            std::string::npos)
      << error;
  std::remove(path.c_str());
}

TEST(VehicleStateFileTest, AnotherVehiclesFileIsRefused) {
  const std::string path = TempStatePath("vehicle_foreign");
  const MessageAuthenticator key = SiteKeyOfByte(0x5a);
  VehicleDescription heavier = Trirotor();
  heavier.arms[1].tip_mass_kg *= 1.1;  // another description: another checksum
  const std::string trirotor = VehicleStateChecksum(Trirotor());
  ASSERT_NE(VehicleStateChecksum(heavier), trirotor);
  std::string error;
  ASSERT_TRUE(WriteVehicleGaugeState(path, Learned(), VehicleStateChecksum(heavier), key, &error)) << error;
  MultiArmGaugeState read;
  EXPECT_FALSE(ReadVehicleGaugeState(path, trirotor, 3, kMaxOffsetRad, key, &read, &error));
  EXPECT_NE(error.find("written for another vehicle description"), std::string::npos) << error;
  EXPECT_FALSE(read.has_tip_mass);
  // The right checksum with another arm count (a forged arm_count line).
  std::string text = VehicleStateText(Learned(), trirotor);
  text.replace(text.find("arm_count: 3"), 12, "arm_count: 4");
  const std::string body = text.substr(0, text.find("checksum: ", text.find("arm_count")));
  SpitSigned(path, body + "checksum: " + TextChecksum(body) + "\n", key);
  EXPECT_FALSE(ReadVehicleGaugeState(path, trirotor, 3, kMaxOffsetRad, key, &read, &error));
  EXPECT_EQ(error, path + ": arm_count 4, the description has 3: refused");
  std::remove(path.c_str());
}

// Each daemon refuses the other's file with a reason that says so, and
// never overwrites it at its stop.
TEST(VehicleStateFileTest, TheBirotorsFileAndThisOneAreNeverTakenForEachOther) {
  const std::string path = TempStatePath("vehicle_kinds");
  const MessageAuthenticator key = SiteKeyOfByte(0x5a);
  const std::string trirotor = VehicleStateChecksum(Trirotor());
  const std::string birotor = VehicleChecksum(BirotorParams());
  GaugeCalibration birotor_state;
  birotor_state.offset_rad[0] = 1e-5;
  birotor_state.offset_std_rad[0] = birotor_state.offset_std_rad[1] = 1e-6;
  std::string error;
  ASSERT_TRUE(WriteGaugeState(path, birotor_state, birotor, key, &error)) << error;
  const std::string birotor_text = Slurp(path);
  MultiArmGaugeState read;
  EXPECT_FALSE(ReadVehicleGaugeState(path, trirotor, 3, kMaxOffsetRad, key, &read, &error));
  EXPECT_EQ(error, path +
                       ": is a birotor gauge state file (birotor-estimator without --vehicle), not a gauge state file "
                       "of a vehicle with N arms (birotor-estimator --vehicle): refused");
  EXPECT_FALSE(WriteVehicleGaugeState(path, Learned(), trirotor, key, &error));
  EXPECT_NE(error.find("exists and is a birotor gauge state file"), std::string::npos) << error;
  EXPECT_NE(error.find("not overwritten"), std::string::npos) << error;
  EXPECT_EQ(Slurp(path), birotor_text);

  std::remove(path.c_str());
  ASSERT_TRUE(WriteVehicleGaugeState(path, Learned(), trirotor, key, &error)) << error;
  const std::string vehicle_text = Slurp(path);
  GaugeCalibration birotor_read;
  EXPECT_FALSE(ReadGaugeState(path, birotor, kMaxOffsetRad, key, &birotor_read, &error));
  EXPECT_NE(error.find("is a gauge state file of a vehicle with N arms"), std::string::npos) << error;
  EXPECT_FALSE(ReadGaugeState(path, birotor, kMaxOffsetRad, &birotor_read, &error));  // the unauthenticated reader
  EXPECT_NE(error.find("is a gauge state file of a vehicle with N arms"), std::string::npos) << error;
  EXPECT_FALSE(WriteGaugeState(path, birotor_state, birotor, key, &error));
  EXPECT_NE(error.find("not overwritten"), std::string::npos) << error;
  EXPECT_EQ(Slurp(path), vehicle_text);
  std::remove(path.c_str());
}

TEST(VehicleStateFileTest, AForgedFileIsRefused) {
  const std::string path = TempStatePath("vehicle_forged");
  const MessageAuthenticator key = SiteKeyOfByte(0x5a);
  const std::string vehicle = VehicleStateChecksum(Trirotor());
  const std::string text = VehicleStateText(Learned(), vehicle);
  MultiArmGaugeState read;
  std::string error;
  Spit(path, text);  // right checksum, no mac
  EXPECT_FALSE(ReadVehicleGaugeState(path, vehicle, 3, kMaxOffsetRad, key, &read, &error));
  EXPECT_NE(error.find("not authenticated (no mac line"), std::string::npos) << error;
  SpitSigned(path, text, SiteKeyOfByte(0x33));  // another key
  EXPECT_FALSE(ReadVehicleGaugeState(path, vehicle, 3, kMaxOffsetRad, key, &read, &error));
  EXPECT_NE(error.find("mac does not verify"), std::string::npos) << error;
  // A genuine file with the ratio changed and the checksum recomputed.
  ASSERT_TRUE(WriteVehicleGaugeState(path, Learned(), vehicle, key, &error)) << error;
  const std::string genuine = Slurp(path);
  MultiArmGaugeState forged = Learned();
  forged.tip_mass_ratio = 0.5;
  Spit(path, VehicleStateText(forged, vehicle) + genuine.substr(genuine.find("mac: ")));
  EXPECT_FALSE(ReadVehicleGaugeState(path, vehicle, 3, kMaxOffsetRad, key, &read, &error));
  EXPECT_NE(error.find("mac does not verify"), std::string::npos) << error;
  EXPECT_FALSE(read.has_tip_mass);
  std::remove(path.c_str());
}

// Signed and checksummed, yet out of range: the reason names the file and
// the field, and nothing is read.
TEST(VehicleStateFileTest, EveryValueIsRangeChecked) {
  const std::string path = TempStatePath("vehicle_ranges");
  const MessageAuthenticator key = SiteKeyOfByte(0x5a);
  const std::string vehicle = VehicleStateChecksum(Trirotor());
  struct Case {
    void (*forge)(MultiArmGaugeState*);
    std::string field;   // the reason starts with it, then the value as written
    std::string reason;  // ... and ends with this
  };
  const Case cases[] = {
      {[](MultiArmGaugeState* s) { s->offset_rad[2] = 6e-4; }, "gauge_offset_rad ",
       " outside [-0.0005, 0.0005] rad (tare.max_offset_rad): refused"},
      {[](MultiArmGaugeState* s) { s->offset_std_rad[1] = 0.5; }, "gauge_offset_std_rad ",
       " outside [1e-09, 0.01] rad (the range of vehicle.gauge_offset_std_rad): refused"},
      {[](MultiArmGaugeState* s) { s->tip_mass_ratio = 2.5; }, "tip_mass_ratio 2.5",
       " outside [0.4, 2] (the tip-mass map's): refused"},
      {[](MultiArmGaugeState* s) { s->tip_mass_ratio_std = 0; }, "tip_mass_ratio_std 0",
       " outside [1e-06, 1]: refused"},
  };
  for (const Case& c : cases) {
    MultiArmGaugeState forged = Learned();
    c.forge(&forged);
    SpitSigned(path, VehicleStateText(forged, vehicle), key);
    MultiArmGaugeState read;
    std::string error;
    EXPECT_FALSE(ReadVehicleGaugeState(path, vehicle, 3, kMaxOffsetRad, key, &read, &error));
    EXPECT_EQ(error.rfind(path + ": " + c.field, 0), 0u) << error;
    ASSERT_GE(error.size(), c.reason.size()) << error;
    EXPECT_EQ(error.substr(error.size() - c.reason.size()), c.reason) << error;
    EXPECT_EQ(std::count(error.begin(), error.end(), '\n'), 0) << error;  // one line
    EXPECT_EQ(read.arm_count, 0);
    EXPECT_FALSE(read.has_tip_mass);
  }
  std::remove(path.c_str());
}

// Written: a sigma beyond the reader's range at its bound (the file claims
// less, never more), a ratio beyond it left out; a non-finite offset is
// not written at all.
TEST(VehicleStateFileTest, TheWriterKeepsToTheReadersRanges) {
  const std::string path = TempStatePath("vehicle_write_ranges");
  const MessageAuthenticator key = SiteKeyOfByte(0x5a);
  const std::string vehicle = VehicleStateChecksum(Trirotor());
  MultiArmGaugeState state = Learned();
  state.offset_std_rad[0] = 1e-12;
  state.tip_mass_ratio_std = 3.0;
  std::string error;
  ASSERT_TRUE(WriteVehicleGaugeState(path, state, vehicle, key, &error)) << error;
  MultiArmGaugeState read;
  ASSERT_TRUE(ReadVehicleGaugeState(path, vehicle, 3, kMaxOffsetRad, key, &read, &error)) << error;
  EXPECT_EQ(read.offset_std_rad[0], 1e-9);
  EXPECT_EQ(read.tip_mass_ratio_std, 1.0);
  state.tip_mass_ratio = 2.5;
  ASSERT_TRUE(WriteVehicleGaugeState(path, state, vehicle, key, &error)) << error;
  ASSERT_TRUE(ReadVehicleGaugeState(path, vehicle, 3, kMaxOffsetRad, key, &read, &error)) << error;
  EXPECT_FALSE(read.has_tip_mass);
  const std::string before = Slurp(path);
  state.offset_rad[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(WriteVehicleGaugeState(path, state, vehicle, key, &error));
  EXPECT_NE(error.find("of arm 2 is not finite: not written"), std::string::npos) << error;
  EXPECT_EQ(Slurp(path), before);
  std::remove(path.c_str());
}

// tare.state_file pointed at the parameter file: refused at start-up and
// never replaced at a stop.
TEST(VehicleStateFileTest, AFileThatIsNotAStateFileIsNeverOverwritten) {
  const std::string path = TempStatePath("vehicle_params");
  const MessageAuthenticator key = SiteKeyOfByte(0x5a);
  const std::string vehicle = VehicleStateChecksum(Trirotor());
  const std::string params = "estimator:\n  method: ekf\n";
  Spit(path, params);
  MultiArmGaugeState read;
  std::string error;
  EXPECT_FALSE(ReadVehicleGaugeState(path, vehicle, 3, kMaxOffsetRad, key, &read, &error));
  EXPECT_FALSE(WriteVehicleGaugeState(path, Learned(), vehicle, key, &error));
  EXPECT_NE(error.find("is not a gauge state file (no '# birotor-estimator gauge offset state, N arms' line)"),
            std::string::npos)
      << error;
  EXPECT_EQ(Slurp(path), params);
  // A symbolic link to it: not followed on reading, not replaced on writing.
  const std::string link = path + ".link";
  ASSERT_EQ(symlink(path.c_str(), link.c_str()), 0);
  EXPECT_FALSE(ReadVehicleGaugeState(link, vehicle, 3, kMaxOffsetRad, key, &read, &error));
  EXPECT_NE(error.find("symbolic link"), std::string::npos) << error;
  EXPECT_FALSE(WriteVehicleGaugeState(link, Learned(), vehicle, key, &error));
  EXPECT_EQ(Slurp(path), params);
  std::remove(link.c_str());
  std::remove(path.c_str());
}

}  // namespace
}  // namespace birotor
