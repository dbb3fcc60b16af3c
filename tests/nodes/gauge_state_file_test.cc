// The persisted gauge offsets (nodes/gauge_state_file.h): round trip,
// atomic replacement, and refusal of corrupt and foreign files.
#include "nodes/gauge_state_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>

namespace birotor {
namespace {

std::string TempStatePath(const std::string& name) {
  return ::testing::TempDir() + "/" + name + "_" + std::to_string(getpid()) + ".state";
}

std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

void Spit(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

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
  const std::string vehicle = VehicleChecksum(VehicleParams());
  std::string error;
  ASSERT_TRUE(WriteGaugeState(path, Learned(), vehicle, &error)) << error;
  EXPECT_NE(access((path + ".tmp").c_str(), F_OK), 0);  // the temporary file was renamed
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

TEST(GaugeStateFileTest, ACorruptFileIsRefusedAndChangesNothing) {
  const std::string path = TempStatePath("corrupt");
  const std::string vehicle = VehicleChecksum(VehicleParams());
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
  VehicleParams other;
  other.tip_mass_kg = 0.3;
  std::string error;
  ASSERT_TRUE(WriteGaugeState(path, Learned(), VehicleChecksum(other), &error));
  GaugeCalibration read;
  EXPECT_FALSE(ReadGaugeState(path, VehicleChecksum(VehicleParams()), 5e-4, &read, &error));
  EXPECT_NE(error.find("another vehicle"), std::string::npos) << error;
  std::remove(path.c_str());
}

TEST(GaugeStateFileTest, AnOffsetOutsideThePhysicalRangeIsRefused) {
  const std::string path = TempStatePath("range");
  GaugeCalibration wild = Learned();
  wild.offset_rad[1] = 2e-3;
  const std::string vehicle = VehicleChecksum(VehicleParams());
  std::string error;
  ASSERT_TRUE(WriteGaugeState(path, wild, vehicle, &error));
  GaugeCalibration read;
  EXPECT_FALSE(ReadGaugeState(path, vehicle, 5e-4, &read, &error));
  EXPECT_NE(error.find("out of range"), std::string::npos) << error;
  std::remove(path.c_str());
}

}  // namespace
}  // namespace birotor
