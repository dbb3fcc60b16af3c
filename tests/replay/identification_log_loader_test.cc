// Reading identification inputs from lcm-logger files, including a file whose
// tail was cut or corrupted.
#include "replay/identification_log_loader.h"

#include <gtest/gtest.h>

#include <fstream>

#include "replay/multi_arm_log_loader.h"
#include "transport/channels.h"
#include "transport/counted_messages.h"
#include "transport/log_io.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

std::string WriteTestLog(const std::string& name, int strain_count) {
  const std::string path = ::testing::TempDir() + "/" + name;
  LogWriter writer;
  std::string error;
  EXPECT_TRUE(writer.Open(path, &error)) << error;
  const ChannelNames channels = MakeChannelNames("TEST_");
  for (int i = 0; i < strain_count; ++i) {
    StrainSample s;
    s.utime = 1000 * i;
    s.seq = i;
    s.deflection_rad[0] = -0.002;
    s.deflection_rad[1] = 0.002;
    writer.WriteMessage(channels.strain, s.utime, ToMessage(s));
    if (i % 2 == 0) {
      MotorSample m;
      m.utime = s.utime;
      m.seq = i / 2;
      writer.WriteMessage(channels.motor, m.utime, ToMessage(m));
    }
  }
  writer.WriteMessage("OTHER_STRAIN", 0, ToMessage(StrainSample()));  // another prefix: ignored
  writer.Close();
  return path;
}

TEST(IdentificationLogLoaderTest, ReadsTheChannelsOfOnePrefix) {
  const std::string path = WriteTestLog("loader_intact.lcm", 100);
  SensorLog log;
  LogLoadReport report;
  std::string error;
  ASSERT_TRUE(LoadSensorLog(path, "TEST_", &log, &report, &error)) << error;
  EXPECT_EQ(log.strain.size(), 100u);
  EXPECT_EQ(log.motor.size(), 50u);
  EXPECT_FALSE(report.truncated_tail);
  EXPECT_EQ(report.decode_errors, 0);
  EXPECT_DOUBLE_EQ(log.strain[10].deflection_rad[1], 0.002);
}

TEST(IdentificationLogLoaderTest, CorruptTailIsReadUpToTheDamage) {
  const std::string path = WriteTestLog("loader_corrupt.lcm", 100);
  {
    std::ofstream out(path, std::ios::app | std::ios::binary);
    const char garbage[] = {'\xED', '\xA1', '\xDA', '\x01', 0x00, 0x00, 0x00, 0x05, 0x12, 0x34};
    out.write(garbage, sizeof(garbage));  // the start of an event, cut
  }
  SensorLog log;
  LogLoadReport report;
  std::string error;
  ASSERT_TRUE(LoadSensorLog(path, "TEST_", &log, &report, &error)) << error;
  EXPECT_TRUE(report.truncated_tail);
  EXPECT_EQ(log.strain.size(), 100u);
  EXPECT_LT(report.tail_offset, report.file_size);
}

TEST(IdentificationLogLoaderTest, MissingFileIsAnError) {
  SensorLog log;
  LogLoadReport report;
  std::string error;
  EXPECT_FALSE(LoadSensorLog("/nonexistent/file.lcm", "TEST_", &log, &report, &error));
  EXPECT_FALSE(error.empty());
}

// The N-arm bench channels of one prefix: each sample keeps its count (3
// here), the VEHICLE message becomes the description, and a 2-arm
// description sees the mismatch (MultiArmLogMismatch).
TEST(MultiArmLogLoaderTest, ReadsTheCountedChannelsAndTheVehicle) {
  const std::string path = ::testing::TempDir() + "/loader_multi_arm.lcm";
  VehicleDescription trirotor;
  trirotor.name = "three";
  trirotor.arm_count = 3;
  trirotor.arms[2].stiffness_n_m_rad = 3000.0;
  {
    LogWriter writer;
    std::string error;
    ASSERT_TRUE(writer.Open(path, &error)) << error;
    const ChannelNames channels = MakeChannelNames("TEST_");
    writer.WriteMessage(channels.vehicle, 0, ToMessage(trirotor, "test"));
    for (int i = 0; i < 10; ++i) {
      MultiArmStrainSample s;
      s.utime = 1000 * i;
      s.n_arms = 3;
      s.deflection_rad = {-0.001, 0.002, 0.003};
      MultiArmLoadCellSample c;
      c.utime = s.utime;
      c.n_rotors = 3;
      c.force_n = {10.0, 11.0, 12.0};
      writer.WriteMessage(channels.strain_n, s.utime, ToMessage(s));
      writer.WriteMessage(channels.loadcell_n, c.utime, ToMessage(c));
      writer.WriteMessage("OTHER_STRAIN_N", s.utime, ToMessage(s));  // another prefix: ignored
    }
    writer.Close();
  }
  MultiArmBenchLog log;
  LogLoadReport report;
  std::string error;
  ASSERT_TRUE(LoadMultiArmBenchLog(path, "TEST_", &log, &report, &error)) << error;
  EXPECT_EQ(log.strain.size(), 10u);
  EXPECT_EQ(log.loadcell.size(), 10u);
  EXPECT_EQ(log.strain[4].n_arms, 3);
  EXPECT_DOUBLE_EQ(log.strain[4].deflection_rad[2], 0.003);
  EXPECT_DOUBLE_EQ(log.loadcell[4].force_n[1], 11.0);
  ASSERT_TRUE(log.has_vehicle);
  EXPECT_EQ(FirstDifference(log.vehicle, trirotor), "");
  EXPECT_EQ(MultiArmLogMismatch(log, trirotor), "");
  EXPECT_EQ(MultiArmLogMismatch(log, VehicleDescription()), path + ": VEHICLE has 3 arms, the description 2");
}

}  // namespace
}  // namespace birotor
