// What `birotor-identify --learned FILE` reads (nodes/learned_values_file.h):
// a gauge state file's strain scales, the newest learned ESTIMATOR_STATUS of
// a flight log, and the refusals (another vehicle, nothing learned, neither
// kind of file). The values are arbitrary test numbers, compared exactly.
#include "nodes/learned_values_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include "nodes/gauge_state_file.h"
#include "nodes/status_message.h"
#include "transport/channels.h"
#include "transport/log_io.h"

namespace birotor {
namespace {

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "/" + name + "_" + std::to_string(getpid());
}

const std::string kVehicle = VehicleChecksum(BirotorParams());

TEST(LearnedValuesFileTest, AStateFileGivesItsStrainScales) {
  const std::string path = TempPath("learned_state");
  GaugeCalibration calibration;
  calibration.has_strain_scale = true;
  calibration.strain_scale[0] = 0.8924;
  calibration.strain_scale[1] = 0.9938;
  calibration.strain_scale_std[0] = 0.0095;
  calibration.strain_scale_std[1] = 0.0094;
  calibration.offset_rad[0] = 3.6e-4;  // above any tare bound: not deployed, not checked
  calibration.offset_std_rad[0] = calibration.offset_std_rad[1] = 1.8e-5;
  std::string error;
  ASSERT_TRUE(WriteGaugeState(path, calibration, kVehicle, &error)) << error;
  LearnedVehicleValues learned;
  ASSERT_TRUE(ReadLearnedValues(path, "", kVehicle, &learned, &error)) << error;
  EXPECT_TRUE(learned.has_strain_scale);
  EXPECT_FALSE(learned.has_body_mass);  // not persisted
  EXPECT_EQ(learned.strain_scale[0], 0.8924);
  EXPECT_EQ(learned.strain_scale_std[1], 0.0094);
  // Another vehicle (e.g. the file already updated with this state): refused.
  BirotorParams other;
  other.gauge_scale[0] = 0.8924;
  EXPECT_FALSE(ReadLearnedValues(path, "", VehicleChecksum(other), &learned, &error));
  EXPECT_NE(error.find("written for another vehicle"), std::string::npos) << error;
  std::remove(path.c_str());
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

TEST(LearnedValuesFileTest, AFlightLogGivesItsNewestLearnedStatus) {
  const std::string path = WriteFlightLog("learned_log", kVehicle);
  LearnedVehicleValues learned;
  std::string error;
  ASSERT_TRUE(ReadLearnedValues(path, "BIROTOR_", kVehicle, &learned, &error)) << error;
  EXPECT_TRUE(learned.has_strain_scale);
  EXPECT_EQ(learned.strain_scale[0], 0.90);
  EXPECT_TRUE(learned.has_body_mass);
  EXPECT_EQ(learned.body_mass_kg, 4.6);
  EXPECT_EQ(learned.body_mass_std_kg, 0.02);
  // On another prefix there is no learned status.
  EXPECT_FALSE(ReadLearnedValues(path, "NONE_", kVehicle, &learned, &error));
  EXPECT_NE(error.find("no NONE_ESTIMATOR_STATUS message with a learned value"), std::string::npos) << error;
  std::remove(path.c_str());
}

TEST(LearnedValuesFileTest, AFlightLogOfAnotherVehicleIsRefused) {
  const std::string path = WriteFlightLog("learned_log_other", "0000000000000000");
  LearnedVehicleValues learned;
  std::string error;
  EXPECT_FALSE(ReadLearnedValues(path, "BIROTOR_", kVehicle, &learned, &error));
  EXPECT_NE(error.find("flown with another vehicle or parameter file (vehicle checksum '0000000000000000', expected " +
                       kVehicle + ")"),
            std::string::npos)
      << error;
  std::remove(path.c_str());
}

TEST(LearnedValuesFileTest, NeitherKindOfFileIsRefused) {
  const std::string path = TempPath("learned_neither");
  std::ofstream(path) << "vehicle:\n  body_mass_kg: 4.0\n";
  LearnedVehicleValues learned;
  std::string error;
  EXPECT_FALSE(ReadLearnedValues(path, "", kVehicle, &learned, &error));
  EXPECT_NE(error.find("not a gauge state file"), std::string::npos) << error;
  EXPECT_NE(error.find("nor an LCM log"), std::string::npos) << error;
  std::remove(path.c_str());
}

}  // namespace
}  // namespace birotor
