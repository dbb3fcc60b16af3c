// birotor-sim --vehicle: the trirotor of config/vehicles/trirotor.yaml flown
// into an LCM log on the counted channels. Read back with transport/log_io:
// every channel at its rate, n_arms the file's in every message, CountMatches
// against the file's description, the description itself on VEHICLE at 1 Hz,
// the same bytes for the same seed; live (published through LCM's file://
// provider, never udpm) the same messages on the same channels; a rotor 3
// fault refused on the birotor and accepted on the trirotor.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "birotor/imu_t.hpp"
#include "birotor/loadcell_n_t.hpp"
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
    } else if (event.channel == c.loadcell_n) {
      const loadcell_n_t m = Decoded<loadcell_n_t>(event, failures);
      facts.count_refusals += CountMatches(m, vehicle, nullptr) && m.n_rotors == 3 ? 0 : 1;
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

// (channel, payload) of every event of a log, in order.
std::vector<std::pair<std::string, std::vector<uint8_t>>> Messages(const std::string& path) {
  LogReader reader;
  std::string error;
  EXPECT_TRUE(reader.Open(path, &error)) << error;
  std::vector<std::pair<std::string, std::vector<uint8_t>>> messages;
  LogEvent event;
  while (reader.Next(&event)) messages.emplace_back(event.channel, event.data);
  return messages;
}

// Live: the same sink path as --output, published through LCM (its file://
// provider records what was published), paced by --speed: the bench
// scenario's messages, byte for byte the log's, LOADCELL_N included.
TEST(MultiArmSimLogTest, LivePublishesWhatTheLogHolds) {
  const VehicleDescription vehicle = LoadVehicleDescription(kTrirotorFile);
  const std::string logged = TempPath("bench.lcm"), published = TempPath("bench_live.lcm");
  const std::string args =
      "--vehicle " + kTrirotorFile + " --scenario " + ScenarioPath("bench") + " --set scenario.duration_s=2 ";
  std::string err;
  ASSERT_EQ(RunSim(args + "--output " + logged, &err), 0) << err;
  // Live, POSE is sealed unless the site lets it through plain (bench.yaml has no POSE; no key here).
  ASSERT_EQ(RunSim(args + "--speed 20 --unsigned POSE --lcm-url 'file://" + published + "?mode=w'", &err), 0) << err;
  const LogFacts facts = ReadLog(published, vehicle);
  EXPECT_EQ(facts.decode_failures, 0);
  EXPECT_EQ(facts.count_refusals, 0);
  EXPECT_EQ(facts.vehicle_mismatches, 0);
  // bench.yaml: IMU and POSE off, the load cells on at 1 kHz; 2 s, VEHICLE at 1 Hz.
  const std::map<std::string, int> expected = {{"BIROTOR_STRAIN_N", 2000},
                                               {"BIROTOR_MOTOR_N", 1000},
                                               {"BIROTOR_LOADCELL_N", 2000},
                                               {"BIROTOR_TRUTH_N", 2000},
                                               {"BIROTOR_VEHICLE", 2}};
  EXPECT_EQ(facts.counts, expected);
  EXPECT_TRUE(Messages(published) == Messages(logged)) << "live and logged messages differ";
  std::remove(logged.c_str());
  std::remove(published.c_str());
}

// The scenario is read for the vehicle's arms: a thrust step on rotor 3 is
// refused at load for the birotor (file, key and range named) and flies on
// the trirotor.
TEST(MultiArmSimLogTest, Rotor3FaultIsRefusedOnTheBirotorAndFliesOnTheTrirotor) {
  const std::string path = TempPath("rotor3.lcm");
  const std::string args = "--scenario " + ScenarioPath("thrust_loss") +
                           " --set scenario.duration_s=2 --set 'faults.thrust_steps=[{time_s: 1.0, rotor: 3, "
                           "scale: 0.8}]' --output " +
                           path;
  std::string err;
  EXPECT_EQ(RunSim(args, &err), 1);
  EXPECT_NE(err.find("thrust_loss.yaml"), std::string::npos) << err;
  EXPECT_NE(err.find("key 'faults.thrust_steps[0].rotor'"), std::string::npos) << err;
  EXPECT_NE(err.find("[1, 2]"), std::string::npos) << err;
  EXPECT_EQ(RunSim("--vehicle " + kTrirotorFile + " " + args, &err), 0) << err;
  EXPECT_NE(err.find("1 fault events"), std::string::npos) << err;
  std::remove(path.c_str());
}

// --vehicle flies the scenario's own autopilot: with --controller it is a
// usage error (exit 2).
TEST(MultiArmSimLogTest, VehicleWithTheLockStepControllerIsAUsageError) {
  std::string err;
  EXPECT_EQ(RunSim("--vehicle " + kTrirotorFile + " --scenario " + ScenarioPath("hover") +
                       " --controller nominal --output " + TempPath("never.lcm"),
                   &err),
            2);
  EXPECT_NE(err.find("--vehicle runs the scenario's own autopilot"), std::string::npos) << err;
}

}  // namespace
}  // namespace birotor
