// The N-arm daemon's start and stop with a gauge state file
// (nodes/multi_arm_state_persistence.h, what birotor-estimator --vehicle
// runs), through the N-arm node behind birotor-replay's replayer on the
// trirotor simulator's packets: a restored file's tip mass is on
// ESTIMATOR_LEARNED_N as state_file, then learned; ESTIMATOR_STATUS says the
// offsets came from the state file; the stop writes the node's state back;
// a birotor state file at the path is refused at the start and left alone
// at the stop; a missing file is a first start.
#include "nodes/multi_arm_state_persistence.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "birotor/estimator_learned_n_t.hpp"
#include "birotor/estimator_status_t.hpp"
#include "nodes/gauge_state_file.h"
#include "nodes/vehicle_state_file.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "replay/replayer.h"
#include "security/site_key.h"
#include "simulator/multi_arm_simulator.h"
#include "sinks/wire_sample_sink.h"
#include "tests/nodes/state_file_test_files.h"
#include "transport/lcm_codec.h"

namespace birotor {
namespace {

std::string SourceFile(const std::string& relative) { return std::string(BIROTOR_SOURCE_DIR) + "/" + relative; }

// Every ESTIMATOR_LEARNED_N's tip-mass source and ESTIMATOR_STATUS's offset source.
class Collector : public MessageSink {
 public:
  explicit Collector(const ChannelNames& channels) : channels_(channels) {}
  void Publish(const std::string& channel, int64_t /*timestamp_us*/, const void* data, size_t size) override {
    if (channel == channels_.estimator_learned_n) {
      estimator_learned_n_t message;
      ASSERT_EQ(DecodeMessage(data, size, &message), DecodeError::kNone);
      tip_mass_sources.push_back(message.tip_mass_source);
      tip_mass_kg.push_back(message.tip_mass_kg[0]);
    } else if (channel == channels_.estimator_status) {
      estimator_status_t message;
      ASSERT_EQ(DecodeMessage(data, size, &message), DecodeError::kNone);
      offset_sources.push_back(message.gauge_offset_source);
    }
  }
  std::vector<std::string> tip_mass_sources, offset_sources;
  std::vector<double> tip_mass_kg;  // arm 1's [kg]

 private:
  ChannelNames channels_;
};

struct Daemon {
  EstimatorConfig config;
  std::string path;
  MessageAuthenticator key = SiteKeyOfByte(0x5a);
};

Daemon TrirotorDaemon(const std::string& name) {
  Daemon d;
  d.config = LoadEstimatorConfig(SourceFile("config/estimator.yaml"));
  d.config.vehicle = LoadVehicleDescription(SourceFile("config/vehicles/trirotor.yaml"));
  d.config.model_consistency.arm_mode_learn_tip_mass = true;
  d.path = ::testing::TempDir() + "/" + name + "_" + std::to_string(getpid()) + ".state";
  return d;
}

// 3 s of the trirotor's gentle flight through the node, with the state
// file restored first (as the daemon does before its first packet).
bool FlyFromStateFile(const Daemon& d, Collector* collector, MultiArmReplayer* replayer) {
  const bool restored = RestoreVehicleGaugeState(d.path, d.config, d.key, &replayer->service());
  VehicleDescription flown = d.config.vehicle;
  for (int i = 0; i < flown.arm_count; ++i) flown.arms[static_cast<size_t>(i)].tip_mass_kg *= 1.1;
  const Scenario scenario = LoadScenario(SourceFile("config/scenarios/gentle.yaml"), {"scenario.duration_s=3"}, 3);
  WireSampleSink wire(MakeChannelNames(), replayer);
  MultiArmSimulator simulator(flown, scenario);
  simulator.Run(&wire);
  EXPECT_FALSE(collector->tip_mass_sources.empty());
  return restored;
}

ReplayOptions FrequentStatus() {
  ReplayOptions options;
  options.status_rate_hz = 50.0;  // the first status within 20 ms of the first sample
  return options;
}

TEST(MultiArmStatePersistence, TheDaemonResumesFromItsStateFileAndWritesItBack) {
  const Daemon d = TrirotorDaemon("multi_arm_daemon_state");
  MultiArmGaugeState persisted;
  persisted.arm_count = 3;
  for (size_t i = 0; i < 3; ++i) persisted.offset_std_rad[i] = 2e-6;
  persisted.has_tip_mass = true;
  persisted.tip_mass_ratio = 1.1;
  persisted.tip_mass_ratio_std = 0.01;
  std::string error;
  ASSERT_TRUE(WriteVehicleGaugeState(d.path, persisted, VehicleStateChecksum(d.config.vehicle), d.key, &error))
      << error;
  Collector collector(MakeChannelNames());
  MultiArmReplayer replayer(d.config, FrequentStatus(), &collector);
  ASSERT_TRUE(FlyFromStateFile(d, &collector, &replayer));
  EXPECT_EQ(collector.tip_mass_sources.front(), "state_file");
  EXPECT_NEAR(collector.tip_mass_kg.front(), 1.1 * d.config.vehicle.arms[0].tip_mass_kg, 1e-12);
  EXPECT_EQ(collector.tip_mass_sources.back(), "learned");  // this run's readings refined it
  EXPECT_EQ(collector.offset_sources.front(), "state_file");

  // The stop: what the node holds now, back into the file.
  ASSERT_TRUE(PersistVehicleGaugeState(d.path, replayer.service(), d.key, &error)) << error;
  MultiArmGaugeState written;
  ASSERT_TRUE(ReadVehicleGaugeState(d.path, VehicleStateChecksum(d.config.vehicle), 3, d.config.tare.max_offset_rad,
                                    d.key, &written, &error))
      << error;
  EXPECT_TRUE(written.has_tip_mass);
  EXPECT_EQ(written.tip_mass_ratio, replayer.service().health().tip_mass_ratio);
  EXPECT_LT(written.tip_mass_ratio_std, persisted.tip_mass_ratio_std);
  // The offsets as the filter holds them at the stop (the persisted ones
  // and what it learned on top in 3 s of flight), bit for bit.
  const MultiArmGaugeState held = replayer.service().GaugeState();
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(written.offset_rad[i], held.offset_rad[i]) << i;
    EXPECT_EQ(written.offset_std_rad[i], held.offset_std_rad[i]) << i;
    EXPECT_NE(written.offset_std_rad[i], persisted.offset_std_rad[i]) << i;  // the filter's, not the file's
  }
  std::remove(d.path.c_str());
}

TEST(MultiArmStatePersistence, ABirotorStateFileIsRefusedAndLeftAlone) {
  const Daemon d = TrirotorDaemon("multi_arm_daemon_birotor_file");
  GaugeCalibration birotor;
  birotor.offset_std_rad[0] = birotor.offset_std_rad[1] = 1e-6;
  birotor.has_tip_mass = true;
  birotor.tip_mass_kg = 0.3;
  birotor.tip_mass_std_kg = 0.003;
  std::string error;
  ASSERT_TRUE(WriteGaugeState(d.path, birotor, VehicleChecksum(BirotorParams()), d.key, &error)) << error;
  const std::string birotor_text = Slurp(d.path);
  Collector collector(MakeChannelNames());
  MultiArmReplayer replayer(d.config, FrequentStatus(), &collector);
  EXPECT_FALSE(FlyFromStateFile(d, &collector, &replayer));
  EXPECT_NE(collector.tip_mass_sources.front(), "state_file");  // the description's m_p,i, then learned
  EXPECT_DOUBLE_EQ(collector.tip_mass_kg.front(), d.config.vehicle.arms[0].tip_mass_kg);
  EXPECT_EQ(collector.offset_sources.front(), "params");
  EXPECT_FALSE(PersistVehicleGaugeState(d.path, replayer.service(), d.key, &error));
  EXPECT_NE(error.find("exists and is a birotor gauge state file"), std::string::npos) << error;
  EXPECT_EQ(Slurp(d.path), birotor_text);
  std::remove(d.path.c_str());
}

TEST(MultiArmStatePersistence, AMissingFileIsAFirstStart) {
  const Daemon d = TrirotorDaemon("multi_arm_daemon_first_start");
  std::remove(d.path.c_str());
  Collector collector(MakeChannelNames());
  MultiArmReplayer replayer(d.config, FrequentStatus(), &collector);
  EXPECT_FALSE(FlyFromStateFile(d, &collector, &replayer));
  EXPECT_EQ(collector.offset_sources.front(), "params");
  std::string error;
  ASSERT_TRUE(PersistVehicleGaugeState(d.path, replayer.service(), d.key, &error)) << error;
  MultiArmGaugeState written;
  EXPECT_TRUE(ReadVehicleGaugeState(d.path, VehicleStateChecksum(d.config.vehicle), 3, d.config.tare.max_offset_rad,
                                    d.key, &written, &error))
      << error;
  EXPECT_TRUE(written.has_tip_mass);  // learning on: the stop persists r and its sigma
  std::remove(d.path.c_str());
}

}  // namespace
}  // namespace birotor
