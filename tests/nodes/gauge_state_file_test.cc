// The persisted gauge offsets (nodes/gauge_state_file.h): round trip,
// atomic replacement, refusal of corrupt and foreign files, and the attacks
// of issue 23 item 6 (planted temporary links, a link, /dev/zero or a FIFO as
// the state file, a forged sigma, the parameter file as the state file).
#include "nodes/gauge_state_file.h"

#include <dirent.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <vector>

#include "tests/nodes/state_file_test_files.h"

namespace birotor {
namespace {

GaugeCalibration Learned() {
  GaugeCalibration c;
  c.offset_rad[0] = 1.4937e-5;
  c.offset_rad[1] = -1.0123e-5;
  c.offset_std_rad[0] = 1.1e-6;
  c.offset_std_rad[1] = 1.2e-6;
  c.source = GaugeOffsetSource::kTare;
  return c;
}

TEST(GaugeStateFileTest, RoundTripKeepsEveryBitAndSaysWhereItCameFrom) {
  const std::string path = TempStatePath("round_trip");
  const std::string vehicle = VehicleChecksum(BirotorParams());
  std::string error;
  ASSERT_TRUE(WriteGaugeState(path, Learned(), vehicle, &error)) << error;
  GaugeCalibration read;
  ASSERT_TRUE(ReadGaugeState(path, vehicle, 5e-4, &read, &error)) << error;
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(read.offset_rad[i], Learned().offset_rad[i]);
    EXPECT_EQ(read.offset_std_rad[i], Learned().offset_std_rad[i]);
    EXPECT_EQ(read.scale[i], 1.0);  // the scale is the parameter file's, not the state's
  }
  EXPECT_EQ(read.source, GaugeOffsetSource::kStateFile);
  std::remove(path.c_str());
}

// The learned strain scale (issue 27) rides along when there is one; a
// file without it reads as before (has_strain_scale false), and a scale
// outside [0.2, 5] is refused like an offset out of range.
TEST(GaugeStateFileTest, ALearnedStrainScaleRoundTripsAndIsRangeChecked) {
  const std::string path = TempStatePath("strain_scale");
  const std::string vehicle = VehicleChecksum(BirotorParams());
  std::string error;
  GaugeCalibration learned = Learned();
  learned.has_strain_scale = true;
  learned.strain_scale[0] = 0.71234567890123;  // gauge scale 0.7 on arm 1 (mismatch_gauge_scale_0p7)
  learned.strain_scale[1] = 1.0012;
  learned.strain_scale_std[0] = 0.0081;
  learned.strain_scale_std[1] = 0.0079;
  ASSERT_TRUE(WriteGaugeState(path, learned, vehicle, &error)) << error;
  EXPECT_NE(Slurp(path).find("strain_scale: 0.71234567890123"), std::string::npos) << Slurp(path);
  GaugeCalibration read;
  ASSERT_TRUE(ReadGaugeState(path, vehicle, 5e-4, &read, &error)) << error;
  EXPECT_TRUE(read.has_strain_scale);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(read.strain_scale[i], learned.strain_scale[i]);
    EXPECT_EQ(read.strain_scale_std[i], learned.strain_scale_std[i]);
    EXPECT_EQ(read.offset_rad[i], learned.offset_rad[i]);
  }
  // Without a learned scale: the old format, read as before.
  ASSERT_TRUE(WriteGaugeState(path, Learned(), vehicle, &error)) << error;
  EXPECT_EQ(Slurp(path).find("strain_scale"), std::string::npos);
  ASSERT_TRUE(ReadGaugeState(path, vehicle, 5e-4, &read, &error)) << error;
  EXPECT_FALSE(read.has_strain_scale);
  // A forged scale with a valid checksum is refused and changes nothing.
  learned.strain_scale[0] = 7.0;
  Spit(path, GaugeStateText(learned, vehicle));
  GaugeCalibration untouched;
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, &untouched, &error));
  EXPECT_NE(error.find("strain_scale"), std::string::npos) << error;
  EXPECT_FALSE(untouched.has_strain_scale);
  EXPECT_EQ(untouched.offset_rad[0], 0.0);
  std::remove(path.c_str());
}

TEST(GaugeStateFileTest, ACorruptFileIsRefusedAndChangesNothing) {
  const std::string path = TempStatePath("corrupt");
  const std::string vehicle = VehicleChecksum(BirotorParams());
  std::string error;
  ASSERT_TRUE(WriteGaugeState(path, Learned(), vehicle, &error));
  std::string text = Slurp(path);
  const size_t field = text.find("gauge_offset_rad: 1.");
  ASSERT_NE(field, std::string::npos) << text;
  text[field + 18] = '2';  // one changed digit: 1.49e-05 -> 2.49e-05
  Spit(path, text);
  GaugeCalibration read;
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, &read, &error));
  EXPECT_NE(error.find("checksum mismatch"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);  // one line
  EXPECT_EQ(read.offset_rad[0], 0.0);
  Spit(path, "garbage\n");
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, &read, &error));
  EXPECT_NE(error.find("not a gauge state file"), std::string::npos) << error;
  EXPECT_FALSE(ReadGaugeState(path + ".absent", vehicle, 5e-4, &read, &error));
  std::remove(path.c_str());
}

TEST(GaugeStateFileTest, AFileOfAnotherVehicleIsRefused) {
  const std::string path = TempStatePath("foreign");
  BirotorParams other;
  other.tip_mass_kg = 0.3;
  std::string error;
  ASSERT_TRUE(WriteGaugeState(path, Learned(), VehicleChecksum(other), &error));
  GaugeCalibration read;
  EXPECT_FALSE(ReadGaugeState(path, VehicleChecksum(BirotorParams()), 5e-4, &read, &error));
  EXPECT_NE(error.find("another vehicle"), std::string::npos) << error;
  std::remove(path.c_str());
}

TEST(GaugeStateFileTest, AnOffsetOutsideThePhysicalRangeIsRefused) {
  const std::string path = TempStatePath("range");
  GaugeCalibration wild = Learned();
  wild.offset_rad[1] = 2e-3;
  const std::string vehicle = VehicleChecksum(BirotorParams());
  std::string error;
  ASSERT_TRUE(WriteGaugeState(path, wild, vehicle, &error));
  GaugeCalibration read;
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, &read, &error));
  EXPECT_NE(error.find("gauge_offset_rad"), std::string::npos) << error;
  EXPECT_NE(error.find("refused"), std::string::npos) << error;
  std::remove(path.c_str());
}

// Issue 23 item 6: a forged file whose checksum was recomputed. The sigma
// 1e300 gave 3798 numerical resets and `inf` written back; every value is
// now range-checked against vehicle.gauge_offset_std_rad's [1e-9, 1e-2] rad.
TEST(GaugeStateFileTest, AForgedSigmaIsRefusedWhateverTheChecksum) {
  const std::string path = TempStatePath("forged");
  const std::string vehicle = VehicleChecksum(BirotorParams());
  for (const double sigma : {1e300, 1e-300, 0.0, -1e-6, 0.011}) {
    GaugeCalibration forged = Learned();
    forged.offset_std_rad[1] = sigma;
    Spit(path, GaugeStateText(forged, vehicle));  // a valid checksum
    GaugeCalibration read;
    std::string error;
    EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, &read, &error)) << sigma;
    EXPECT_NE(error.find("gauge_offset_std_rad"), std::string::npos) << error;
    EXPECT_EQ(read.offset_std_rad[1], 0.0);  // unchanged
  }
  GaugeCalibration forged = Learned();
  forged.offset_rad[0] = std::numeric_limits<double>::infinity();
  Spit(path, GaugeStateText(forged, vehicle));
  GaugeCalibration read;
  std::string error;
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, &read, &error));
  std::remove(path.c_str());
}

// A value that cannot be read back is never written: inf refused, a std
// below the reader's 1e-9 rad floored to it.
TEST(GaugeStateFileTest, WhatIsWrittenReadsBack) {
  const std::string path = TempStatePath("write_range");
  const std::string vehicle = VehicleChecksum(BirotorParams());
  GaugeCalibration bad = Learned();
  bad.offset_std_rad[0] = std::numeric_limits<double>::infinity();
  std::string error;
  EXPECT_FALSE(WriteGaugeState(path, bad, vehicle, &error));
  EXPECT_NE(access(path.c_str(), F_OK), 0);
  GaugeCalibration tiny = Learned();
  tiny.offset_std_rad[0] = 1e-12;
  ASSERT_TRUE(WriteGaugeState(path, tiny, vehicle, &error)) << error;
  GaugeCalibration read;
  ASSERT_TRUE(ReadGaugeState(path, vehicle, 5e-4, &read, &error)) << error;
  EXPECT_EQ(read.offset_std_rad[0], 1e-9);
  std::remove(path.c_str());
}

std::vector<std::string> FolderEntries(const std::string& folder) {
  std::vector<std::string> names;
  DIR* dir = opendir(folder.c_str());
  while (dirent* entry = readdir(dir)) {
    const std::string name = entry->d_name;
    if (name != "." && name != "..") names.push_back(name);
  }
  closedir(dir);
  return names;
}

std::string MakeFolder(const std::string& name) {
  std::string folder = ::testing::TempDir() + "/gauge_state_" + name + "_XXXXXX";
  EXPECT_NE(mkdtemp(folder.data()), nullptr);
  return folder;
}

// The old writer used the fixed name <state>.tmp with fopen("w"): a planted
// symlink or hard link of that name made the root daemon overwrite its
// target. The temporary name is now unique and created with O_EXCL.
TEST(GaugeStateFileTest, APlantedTemporaryLinkIsNeverWrittenThrough) {
  const std::string folder = MakeFolder("planted");
  const std::string path = folder + "/gauge.state";
  const std::string victim = folder + "/victim";
  Spit(victim, "precious\n");
  ASSERT_EQ(symlink(victim.c_str(), (path + ".tmp").c_str()), 0);
  ASSERT_EQ(link(victim.c_str(), (folder + "/.gauge.state.tmp").c_str()), 0);
  std::string error;
  const std::string vehicle = VehicleChecksum(BirotorParams());
  ASSERT_TRUE(WriteGaugeState(path, Learned(), vehicle, &error)) << error;
  ASSERT_TRUE(WriteGaugeState(path, Learned(), vehicle, &error)) << error;  // over the existing state
  EXPECT_EQ(Slurp(victim), "precious\n");
  GaugeCalibration read;
  EXPECT_TRUE(ReadGaugeState(path, vehicle, 5e-4, &read, &error)) << error;
  EXPECT_EQ(FolderEntries(folder).size(), 4u);  // no temporary left behind
  std::filesystem::remove_all(folder);
}

// A state_file that is a symbolic link (to a victim, or to /dev/zero) is
// neither read nor written through.
TEST(GaugeStateFileTest, AStateFileThatIsALinkIsRefused) {
  const std::string folder = MakeFolder("link");
  const std::string path = folder + "/gauge.state";
  const std::string victim = folder + "/victim";
  const std::string vehicle = VehicleChecksum(BirotorParams());
  std::string error;
  ASSERT_TRUE(WriteGaugeState(victim, Learned(), vehicle, &error)) << error;  // even a valid state file
  const std::string victim_text = Slurp(victim);
  ASSERT_EQ(symlink(victim.c_str(), path.c_str()), 0);
  GaugeCalibration read;
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, &read, &error));
  EXPECT_NE(error.find("symbolic link"), std::string::npos) << error;
  GaugeCalibration other = Learned();
  other.offset_rad[0] = 0.0;
  EXPECT_FALSE(WriteGaugeState(path, other, vehicle, &error));
  EXPECT_NE(error.find("symbolic link"), std::string::npos) << error;
  EXPECT_EQ(Slurp(victim), victim_text);
  struct stat info {};
  ASSERT_EQ(lstat(path.c_str(), &info), 0);
  EXPECT_TRUE(S_ISLNK(info.st_mode));  // the link itself is left too
  std::filesystem::remove_all(folder);
}

// /dev/zero grew the daemon to 1 GB before the size check; a FIFO hung the
// start-up. Both are refused by type before a byte is read (a hang here
// would be the test's time-out).
TEST(GaugeStateFileTest, DevicesAndFifosAreRefusedWithoutReadingOrWaiting) {
  const std::string folder = MakeFolder("special");
  const std::string fifo = folder + "/gauge.fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string vehicle = VehicleChecksum(BirotorParams());
  GaugeCalibration read;
  std::string error;
  EXPECT_FALSE(ReadGaugeState(fifo, vehicle, 5e-4, &read, &error));
  EXPECT_NE(error.find("a FIFO"), std::string::npos) << error;
  EXPECT_FALSE(WriteGaugeState(fifo, Learned(), vehicle, &error));  // would block on open
  EXPECT_NE(error.find("a FIFO"), std::string::npos) << error;
  EXPECT_FALSE(ReadGaugeState("/dev/zero", vehicle, 5e-4, &read, &error));
  EXPECT_NE(error.find("character device"), std::string::npos) << error;
  EXPECT_FALSE(WriteGaugeState("/dev/null", Learned(), vehicle, &error));
  EXPECT_FALSE(ReadGaugeState(folder, vehicle, 5e-4, &read, &error));
  EXPECT_NE(error.find("a folder"), std::string::npos) << error;
  const std::string big = folder + "/big.state";
  Spit(big, "# birotor-estimator gauge offset state\n" + std::string(5000, '#'));
  EXPECT_FALSE(ReadGaugeState(big, vehicle, 5e-4, &read, &error));
  EXPECT_NE(error.find("larger than 4096 bytes"), std::string::npos) << error;
  EXPECT_EQ(read.source, GaugeOffsetSource::kParameters);
  std::filesystem::remove_all(folder);
}

// state_file pointed at the parameter file: refused at start-up as not a
// state file, and (whatever the start-up did) never replaced at stop.
TEST(GaugeStateFileTest, AFileThatIsNotAStateFileIsNeverOverwritten) {
  const std::string folder = MakeFolder("params");
  const std::string path = folder + "/estimator.yaml";
  const std::string params = "vehicle:\n  body_mass_kg: 1.2\n";
  Spit(path, params);
  const std::string vehicle = VehicleChecksum(BirotorParams());
  GaugeCalibration read;
  std::string error;
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, &read, &error));
  EXPECT_FALSE(WriteGaugeState(path, Learned(), vehicle, &error));
  EXPECT_NE(error.find("is not a gauge state file"), std::string::npos) << error;
  EXPECT_NE(error.find("not overwritten"), std::string::npos) << error;
  EXPECT_EQ(Slurp(path), params);
  std::filesystem::remove_all(folder);
}

// A replaced state file keeps its mode (the old writer gave 0644 or 0666).
TEST(GaugeStateFileTest, AReplacedStateFileKeepsItsMode) {
  const std::string folder = MakeFolder("mode");
  const std::string path = folder + "/gauge.state";
  const std::string vehicle = VehicleChecksum(BirotorParams());
  std::string error;
  ASSERT_TRUE(WriteGaugeState(path, Learned(), vehicle, &error)) << error;
  struct stat info {};
  ASSERT_EQ(stat(path.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 07777, 0644u);  // a new file
  ASSERT_EQ(chmod(path.c_str(), 0600), 0);
  ASSERT_TRUE(WriteGaugeState(path, Learned(), vehicle, &error)) << error;
  ASSERT_EQ(stat(path.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 07777, 0600u);
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace birotor

namespace birotor {
namespace {

// Issue 37 item 4: the daemon's state file carries a MAC under the site key.
SiteKey TestSiteKey(uint8_t fill) {
  SiteKey::Bytes bytes;
  bytes.fill(fill);
  return SiteKey(bytes);
}

std::string AuthenticatedStatePath(const std::string& name) {
  return ::testing::TempDir() + "/" + name + "_" + std::to_string(getpid()) + ".mac.state";
}

TEST(AuthenticatedGaugeStateTest, AGenuineFileRestoresEveryBit) {
  const std::string path = AuthenticatedStatePath("genuine");
  const std::string vehicle = VehicleChecksum(BirotorParams());
  const MessageAuthenticator authenticator(TestSiteKey(0x11));
  std::string error;
  ASSERT_TRUE(WriteGaugeState(path, Learned(), vehicle, authenticator, &error)) << error;
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t mac_at = text.find("\nmac: ");
  ASSERT_NE(mac_at, std::string::npos) << text;
  EXPECT_EQ(text.size() - mac_at, 1 + 5 + 64 + 1u);  // "mac: ", 32 bytes in hex, newline: the last line
  GaugeCalibration read;
  ASSERT_TRUE(ReadGaugeState(path, vehicle, 5e-4, authenticator, &read, &error)) << error;
  EXPECT_EQ(read.offset_rad[0], Learned().offset_rad[0]);
  EXPECT_EQ(read.offset_rad[1], Learned().offset_rad[1]);
  EXPECT_EQ(read.source, GaugeOffsetSource::kStateFile);
  // The unauthenticated reader (the kind probe of birotor-identify --learned) skips the mac line.
  GaugeCalibration unauthenticated;
  ASSERT_TRUE(ReadGaugeState(path, vehicle, 5e-4, &unauthenticated, &error)) << error;
  EXPECT_EQ(unauthenticated.offset_rad[1], Learned().offset_rad[1]);
  unlink(path.c_str());
}

// Offsets the offset-departure test says took a force (a payload, docs/
// mismatch.md "Offsets that took a force") are not kept: the state holds the
// anchor they left, with its sigma, so that the next start sees the payload
// again; offsets that did not depart are kept as learned.
TEST(GaugeStatePersistence, OffsetsThatDepartedAreReplacedByTheirAnchor) {
  PipelineHealth health;
  health.gauge = Learned();
  OffsetDepartureState& offsets = health.consistency.offsets;
  offsets.anchor_rad[0] = 1.5e-5;
  offsets.anchor_rad[1] = -1.0e-5;
  offsets.anchor_std_rad[0] = offsets.anchor_std_rad[1] = 5e-5;
  GaugeCalibration state = PersistedGaugeState(health);
  EXPECT_EQ(state.offset_rad[0], Learned().offset_rad[0]);
  EXPECT_EQ(state.offset_std_rad[1], Learned().offset_std_rad[1]);
  offsets.departed = true;
  state = PersistedGaugeState(health);
  EXPECT_EQ(state.offset_rad[0], 1.5e-5);
  EXPECT_EQ(state.offset_rad[1], -1.0e-5);
  EXPECT_EQ(state.offset_std_rad[0], 5e-5);
  EXPECT_EQ(state.offset_std_rad[1], 5e-5);
  EXPECT_EQ(state.source, Learned().source);
}

// The tip mass learned from the arm mode (issue 36) is persisted from the
// pipeline's health (PersistedGaugeState), under the mac; out of the range
// of vehicle.tip_mass_kg, or its sigma outside [1e-6, 1] kg, it is refused
// naming the file and the key, and a changed value with its checksum
// recomputed does not verify. Values: the tip mass +20 % flight's
// (tests/nodes/estimator_learned_message_test.cc).
TEST(AuthenticatedGaugeStateTest, ALearnedTipMassIsPersistedAndChecked) {
  const std::string path = AuthenticatedStatePath("tip_mass");
  const std::string vehicle = VehicleChecksum(BirotorParams());
  const MessageAuthenticator authenticator(TestSiteKey(0x11));
  PipelineHealth health;
  health.gauge = Learned();
  health.tip_mass_learned = true;
  health.tip_mass_kg = 0.34344712345678;
  health.tip_mass_std_kg = 0.0031679;
  const GaugeCalibration state = PersistedGaugeState(health);
  std::string error;
  ASSERT_TRUE(WriteGaugeState(path, state, vehicle, authenticator, &error)) << error;
  GaugeCalibration read;
  ASSERT_TRUE(ReadGaugeState(path, vehicle, 5e-4, authenticator, &read, &error)) << error;
  EXPECT_TRUE(read.has_tip_mass);
  EXPECT_EQ(read.tip_mass_kg, 0.34344712345678);
  EXPECT_EQ(read.tip_mass_std_kg, 0.0031679);
  EXPECT_EQ(read.offset_rad[0], Learned().offset_rad[0]);
  // Not learned: no tip-mass lines, read as before.
  health.tip_mass_learned = false;
  ASSERT_TRUE(WriteGaugeState(path, PersistedGaugeState(health), vehicle, authenticator, &error)) << error;
  ASSERT_TRUE(ReadGaugeState(path, vehicle, 5e-4, authenticator, &read, &error)) << error;
  EXPECT_FALSE(read.has_tip_mass);
  EXPECT_EQ(Slurp(path).find("tip_mass"), std::string::npos);
  // Out of range with a right checksum (the plain reader: the mac is not
  // what refuses it), one line naming the file and the key.
  GaugeCalibration forged = state;
  forged.tip_mass_kg = 150.0;
  Spit(path, GaugeStateText(forged, vehicle));
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, &read, &error));
  EXPECT_EQ(error, path + ": tip_mass_kg 150 outside [0.0001, 100] kg (the range of vehicle.tip_mass_kg): refused");
  forged = state;
  forged.tip_mass_std_kg = 2.0;
  Spit(path, GaugeStateText(forged, vehicle));
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, &read, &error));
  EXPECT_EQ(error, path + ": tip_mass_std_kg 2 outside [1e-06, 1] kg: refused");
  // Written: a sigma beyond the range at its bound (the file claims less,
  // never more); a tip mass beyond it left out (learned again next start).
  ASSERT_TRUE(WriteGaugeState(path, forged, vehicle, authenticator, &error)) << error;
  ASSERT_TRUE(ReadGaugeState(path, vehicle, 5e-4, authenticator, &read, &error)) << error;
  EXPECT_EQ(read.tip_mass_std_kg, 1.0);
  forged.tip_mass_kg = 150.0;
  ASSERT_TRUE(WriteGaugeState(path, forged, vehicle, authenticator, &error)) << error;
  ASSERT_TRUE(ReadGaugeState(path, vehicle, 5e-4, authenticator, &read, &error)) << error;
  EXPECT_FALSE(read.has_tip_mass);
  // A genuine file with the tip mass changed and the checksum recomputed.
  ASSERT_TRUE(WriteGaugeState(path, state, vehicle, authenticator, &error)) << error;
  const std::string text = Slurp(path);
  forged = state;
  forged.tip_mass_kg = 0.5;
  Spit(path, GaugeStateText(forged, vehicle) + text.substr(text.find("mac: ")));
  GaugeCalibration untouched;
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, authenticator, &untouched, &error));
  EXPECT_NE(error.find("mac does not verify"), std::string::npos) << error;
  EXPECT_FALSE(untouched.has_tip_mass);
  unlink(path.c_str());
}

TEST(AuthenticatedGaugeStateTest, AForgedFileWithValidContentIsRefusedAndNotApplied) {
  const std::string path = AuthenticatedStatePath("forged");
  const std::string vehicle = VehicleChecksum(BirotorParams());
  const MessageAuthenticator authenticator(TestSiteKey(0x11));
  GaugeCalibration forged = Learned();
  forged.offset_rad[0] = 4.9e-4;  // in range (tare.max_offset_rad 5e-4), right checksum
  std::string error;
  GaugeCalibration read;
  read.offset_rad[0] = 7.0;
  // Missing MAC: the plain file a forger writes with a recomputed checksum.
  ASSERT_TRUE(WriteGaugeState(path, forged, vehicle, &error)) << error;
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, authenticator, &read, &error));
  EXPECT_EQ(error, path + ": not authenticated (no mac line; written without the site key or forged)");
  // Wrong MAC: made with another key.
  ASSERT_TRUE(WriteGaugeState(path, forged, vehicle, MessageAuthenticator(TestSiteKey(0x22)), &error)) << error;
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, authenticator, &read, &error));
  EXPECT_EQ(error,
            path + ": not authenticated (mac does not verify under the site key: forged, altered or another key)");
  // A genuine file with one value changed and its checksum recomputed.
  ASSERT_TRUE(WriteGaugeState(path, Learned(), vehicle, authenticator, &error)) << error;
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string mac_line = text.substr(text.find("mac: "));
  std::ofstream(path) << GaugeStateText(forged, vehicle) + mac_line;
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, authenticator, &read, &error));
  EXPECT_NE(error.find("mac does not verify"), std::string::npos) << error;
  EXPECT_EQ(read.offset_rad[0], 7.0);  // not applied
  unlink(path.c_str());
}

}  // namespace
}  // namespace birotor
