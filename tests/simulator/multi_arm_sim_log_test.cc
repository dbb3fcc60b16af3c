// birotor-sim --vehicle: the trirotor of config/vehicles/trirotor.yaml flown
// into an LCM log on the counted channels. Read back with transport/log_io:
// every channel at its rate, n_arms the file's in every message, CountMatches
// against the file's description, the description itself on VEHICLE at 1 Hz,
// the same bytes for the same seed; --vehicle needs --output.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "birotor/imu_t.hpp"
#include "birotor/pose_t.hpp"
#include "params/vehicle_description_yaml.h"
#include "tests/simulator/test_support.h"
#include "transport/channels.h"
#include "transport/counted_messages.h"
#include "transport/lcm_codec.h"
#include "transport/log_io.h"

namespace birotor {
namespace {

const std::string kTrirotorFile = std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml";

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "multi_arm_sim_log_test_" + std::to_string(::getpid()) + "_" + name;
}

int RunSim(const std::string& args, std::string* err) {
  return RunProgram(BIROTOR_SIM_PATH, args, TempPath("stderr.txt"), err);
}

// Decodes event as Message; counts a failure or a count that does not match.
template <typename Message>
Message Decoded(const LogEvent& event, int* failures) {
  Message m;
  if (DecodeMessage(event.data.data(), event.data.size(), &m) != DecodeError::kNone) ++*failures;
  return m;
}

struct LogFacts {
  std::map<std::string, int> counts;
  int decode_failures = 0;
  int count_refusals = 0;      // CountMatches false
  int vehicle_mismatches = 0;  // VEHICLE not the file's description
  int nan_strain = 0;          // strain entries not finite
};

LogFacts ReadLog(const std::string& path, const VehicleDescription& vehicle) {
  LogReader reader;
  std::string error;
  EXPECT_TRUE(reader.Open(path, &error)) << error;
  const ChannelNames c = MakeChannelNames();
  LogFacts facts;
  LogEvent event;
  while (reader.Next(&event)) {
    ++facts.counts[event.channel];
    int* failures = &facts.decode_failures;
    if (event.channel == c.strain_n) {
      const strain_n_t m = Decoded<strain_n_t>(event, failures);
      facts.count_refusals += CountMatches(m, vehicle, nullptr) && m.n_arms == 3 ? 0 : 1;
      for (double b : m.deflection_rad) facts.nan_strain += std::isfinite(b) ? 0 : 1;
    } else if (event.channel == c.motor_n) {
      const motor_n_t m = Decoded<motor_n_t>(event, failures);
      facts.count_refusals += CountMatches(m, vehicle, nullptr) && m.n_rotors == 3 ? 0 : 1;
    } else if (event.channel == c.truth_n) {
      const truth_n_t m = Decoded<truth_n_t>(event, failures);
      facts.count_refusals += CountMatches(m, vehicle, nullptr) && m.n_arms == 3 ? 0 : 1;
    } else if (event.channel == c.vehicle) {
      const vehicle_description_t m = Decoded<vehicle_description_t>(event, failures);
      VehicleDescription from_wire;
      std::string why;
      const bool same = FromMessage(m, &from_wire, &why) && FirstDifference(from_wire, vehicle).empty();
      facts.vehicle_mismatches += same && m.n_arms == 3 ? 0 : 1;
    } else if (event.channel == c.imu) {
      Decoded<imu_t>(event, failures);
    } else if (event.channel == c.pose) {
      Decoded<pose_t>(event, failures);
    } else {
      ++facts.decode_failures;  // a channel --vehicle does not write
    }
  }
  return facts;
}

TEST(MultiArmSimLogTest, TrirotorFileIntoALogOnTheCountedChannels) {
  const VehicleDescription vehicle = LoadVehicleDescription(kTrirotorFile);
  const std::string path = TempPath("trirotor.lcm"), again = TempPath("trirotor_again.lcm");
  const std::string args =
      "--vehicle " + kTrirotorFile + " --scenario " + ScenarioPath("hover") + " --set scenario.duration_s=3 --output ";
  std::string err;
  ASSERT_EQ(RunSim(args + path, &err), 0) << err;
  const LogFacts facts = ReadLog(path, vehicle);
  EXPECT_EQ(facts.decode_failures, 0);
  EXPECT_EQ(facts.count_refusals, 0);
  EXPECT_EQ(facts.vehicle_mismatches, 0);
  EXPECT_EQ(facts.nan_strain, 0);  // every trirotor arm has a gauge
  // 3 s at the reference rates (reference-vehicle.md), VEHICLE at 1 Hz.
  const std::map<std::string, int> expected = {{"BIROTOR_STRAIN_N", 3000}, {"BIROTOR_MOTOR_N", 1500},
                                               {"BIROTOR_IMU", 3000},      {"BIROTOR_POSE", 300},
                                               {"BIROTOR_TRUTH_N", 3000},  {"BIROTOR_VEHICLE", 3}};
  EXPECT_EQ(facts.counts, expected);
  ASSERT_EQ(RunSim(args + again, &err), 0) << err;
  EXPECT_TRUE(ReadFileBytes(path) == ReadFileBytes(again)) << "same seed, different bytes";
  std::remove(path.c_str());
  std::remove(again.c_str());
}

// --vehicle is offline: without --output it is a usage error (exit 2).
TEST(MultiArmSimLogTest, VehicleWithoutAnOutputLogIsAUsageError) {
  std::string err;
  EXPECT_EQ(RunSim("--vehicle " + kTrirotorFile + " --scenario " + ScenarioPath("hover"), &err), 2);
  EXPECT_NE(err.find("--vehicle runs offline into --output"), std::string::npos) << err;
}

}  // namespace
}  // namespace birotor
