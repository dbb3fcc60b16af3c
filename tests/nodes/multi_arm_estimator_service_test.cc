// The N-arm estimator node (nodes/multi_arm_estimator_service.h) behind
// birotor-replay --vehicle: the trirotor simulator's packets on the counted
// channels in, one FORCE_N per strain sample out (decodable, three rotors,
// finite, VALID once converged, the rotor's fault bit after a loss), and
// ESTIMATOR_STATUS on the vehicle clock; a packet that does not decode, or
// carries another vehicle's count, is counted as a decode error of its input
// and never reaches the filter; ESTIMATOR_STATUS carries the fusion counters
// of every input, the accelerometer's and the method's name.
#include "nodes/multi_arm_estimator_service.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_n_t.hpp"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "replay/replayer.h"
#include "simulator/multi_arm_simulator.h"
#include "sinks/wire_sample_sink.h"
#include "transport/lcm_codec.h"

namespace birotor {
namespace {

std::string SourceFile(const std::string& relative) { return std::string(BIROTOR_SOURCE_DIR) + "/" + relative; }

// Every FORCE_N and ESTIMATOR_STATUS the replay writes.
class Collector : public MessageSink {
 public:
  explicit Collector(const ChannelNames& channels) : channels_(channels) {}
  void Publish(const std::string& channel, int64_t /*timestamp_us*/, const void* data, size_t size) override {
    if (channel == channels_.estimator_status) {
      ++statuses;
      ASSERT_EQ(DecodeMessage(data, size, &last_status), DecodeError::kNone);
    }
    if (channel != channels_.force_n) return;
    force_estimate_n_t message;
    ASSERT_EQ(DecodeMessage(data, size, &message), DecodeError::kNone);
    forces.push_back(message);
  }
  std::vector<force_estimate_n_t> forces;
  int statuses = 0;
  estimator_status_t last_status;

 private:
  ChannelNames channels_;
};

struct Flight {
  EstimatorConfig config;
  Scenario scenario;
};

// The trirotor's thrust_loss, 8 s: rotor 2 at 75 % from 5 s.
Flight TrirotorLoss() {
  Flight f;
  f.config = LoadEstimatorConfig(SourceFile("config/estimator.yaml"));
  f.config.vehicle = LoadVehicleDescription(SourceFile("config/vehicles/trirotor.yaml"));
  f.scenario = LoadScenario(SourceFile("config/scenarios/thrust_loss.yaml"), {"scenario.duration_s=8"}, 3);
  return f;
}

// The flight's simulated packets through the node behind the replayer.
void Fly(const Flight& f, MultiArmReplayer* replayer) {
  WireSampleSink wire(MakeChannelNames(), replayer);
  MultiArmSimulator simulator(f.config.vehicle, f.scenario);
  simulator.Run(&wire);
}

TEST(MultiArmEstimatorServiceTest, OneForcePerStrainSampleWithTheLossFlagged) {
  const Flight f = TrirotorLoss();
  Collector collector(MakeChannelNames());
  MultiArmReplayer replayer(f.config, ReplayOptions{}, &collector);
  Fly(f, &replayer);
  ASSERT_EQ(collector.forces.size(), 8000u);  // 8 s at 1 kHz
  EXPECT_EQ(replayer.stats().forces, 8000);
  EXPECT_EQ(replayer.stats().truth_copied, 8000);
  EXPECT_GE(collector.statuses, 39);  // 5 Hz on the vehicle clock
  EXPECT_EQ(replayer.service().health().resets, 1);
  int first_fault_ms = -1;
  for (size_t k = 0; k < collector.forces.size(); ++k) {
    const force_estimate_n_t& m = collector.forces[k];
    ASSERT_EQ(m.n_rotors, 3);
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(std::isfinite(m.force_n[static_cast<size_t>(i)]));
    if (first_fault_ms < 0 && (m.rotor_fault_bits & 2) != 0) first_fault_ms = static_cast<int>(k);
  }
  EXPECT_NE(collector.forces[4000].status & kStatusValid, 0);
  // Rotor 2 at 75 % from 5.000 s: flagged 10 ms later (measured), nothing before.
  EXPECT_GE(first_fault_ms, 5000);
  EXPECT_LE(first_fault_ms, 5015);
}

TEST(MultiArmEstimatorServiceTest, StatusCarriesTheFusionCountersOfEveryInput) {
  Flight f = TrirotorLoss();
  f.scenario = LoadScenario(SourceFile("config/scenarios/hover.yaml"), {"scenario.duration_s=2"}, 3);
  Collector collector(MakeChannelNames());
  MultiArmReplayer replayer(f.config, ReplayOptions{}, &collector);
  Fly(f, &replayer);
  ASSERT_GE(collector.statuses, 9);
  const estimator_status_t& status = collector.last_status;
  EXPECT_EQ(status.method, "ekf");
  ASSERT_EQ(status.num_inputs, 4);
  const input_health_t& strain = status.inputs[0];
  const input_health_t& motor = status.inputs[1];
  const input_health_t& imu = status.inputs[2];
  EXPECT_EQ(strain.channel, "STRAIN");
  // At the last status (1.8 s of the 2 s): every strain sample but the
  // first fused, the motor's and gyro's too, the accelerometer's on its own.
  EXPECT_GT(strain.fused, 1700);
  EXPECT_EQ(strain.rejected_gate, 0);
  EXPECT_GT(motor.fused, 850);
  EXPECT_GT(imu.fused, 1700);
  EXPECT_GT(status.accelerometer.fused, 1700);
  EXPECT_EQ(status.accelerometer.channel, "IMU accel_z");
  EXPECT_EQ(strain.gate, f.config.ekf.strain_gate_nis);
  EXPECT_EQ(status.strain_gate, f.config.ekf.strain_gate_nis);
  EXPECT_EQ(status.accelerometer.gate, f.config.ekf.accel_gate_nis);
  // The period's mean NIS near the strain's 3 degrees of freedom.
  EXPECT_NEAR(status.strain_nis_mean, 3.0, 0.6);
  EXPECT_NEAR(status.accelerometer.nis_mean, 2.0, 0.6);
}

TEST(MultiArmEstimatorServiceTest, GarbageAndAnotherVehiclesCountAreDecodeErrors) {
  const Flight f = TrirotorLoss();
  const ChannelNames channels = MakeChannelNames();
  Collector collector(channels);
  MultiArmEstimatorService service(f.config, channels, EstimatorServiceOptions(), &collector);
  const uint8_t garbage[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  service.HandlePacket(channels.strain_n, garbage, sizeof(garbage), -1);
  strain_n_t birotor_strain{};
  birotor_strain.utime = 1000;
  birotor_strain.n_arms = 2;
  birotor_strain.deflection_rad = {0.001, 0.001};
  std::vector<uint8_t> bytes;
  EncodeMessage(birotor_strain, &bytes);
  service.HandlePacket(channels.strain_n, bytes.data(), bytes.size(), -1);
  const InputCounters& strain = service.health().inputs[static_cast<int>(InputChannel::kStrain)];
  EXPECT_EQ(strain.received, 2);
  EXPECT_EQ(strain.decode_errors, 2);
  EXPECT_EQ(service.arm_count_refusals().strain.mismatch, 1);
  EXPECT_EQ(service.forces_published(), 0);
  EXPECT_TRUE(collector.forces.empty());
  // The birotor's own channels are not this node's.
  EXPECT_FALSE(service.IsInputChannel(channels.strain));
  EXPECT_TRUE(service.IsInputChannel(channels.strain_n));
}

}  // namespace
}  // namespace birotor
