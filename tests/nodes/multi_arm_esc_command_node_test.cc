// The N-rotor simulator's ESC input (nodes/multi_arm_esc_command_node.h) on
// the trirotor: MOTOR_COMMAND_N of the vehicle's count is run, another count
// is a decode error (counted, never run), a speed above omega_max and a
// stale stamp are refused by the ESCs' rule, and after the command timeout
// the ESCs command 0.
#include "nodes/multi_arm_esc_command_node.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "params/vehicle_description_yaml.h"
#include "transport/lcm_codec.h"

namespace birotor {
namespace {

std::vector<uint8_t> Command(int n, int64_t utime, int32_t seq, double omega_rad_s) {
  motor_command_n_t m{};
  m.utime = utime;
  m.seq = seq;
  m.n_rotors = static_cast<int8_t>(n);
  m.omega_cmd_rad_s.assign(static_cast<size_t>(n), omega_rad_s);
  std::vector<uint8_t> bytes;
  EncodeMessage(m, &bytes);
  return bytes;
}

class MultiArmEscCommandNodeTest : public ::testing::Test {
 protected:
  MultiArmEscCommandNodeTest() { sim_.UseExternalCommands(); }
  static Scenario Hover() {
    Scenario scenario;
    scenario.name = "test";
    scenario.arm_count = 3;
    scenario.duration_s = 1.0;
    return scenario;
  }
  void Send(const std::vector<uint8_t>& bytes) { node_.HandlePacket(kChannel, bytes.data(), bytes.size(), -1); }
  // Steps the simulator by n steps, the node ticking before each.
  void Step(int n) {
    for (int k = 0; k < n; ++k) {
      node_.Tick();
      sim_.Step();
    }
  }

  const std::string kChannel = "TEST_MOTOR_COMMAND_N";
  const VehicleDescription vehicle_ =
      LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml");
  MultiArmSimulator sim_{vehicle_, Hover()};
  MultiArmEscCommandNode node_{kChannel, &sim_, 0.1};
};

TEST_F(MultiArmEscCommandNodeTest, RunsItsCountRefusesOthersAndSpoolsDownAfterTheTimeout) {
  Step(4);  // 1 ms (4 kHz steps)
  Send(Command(3, sim_.utime(), 1, 500.0));
  EXPECT_EQ(node_.rule().counters().accepted, 1);
  Step(1);
  EXPECT_DOUBLE_EQ(sim_.input().omega_cmd_rad_s[2], 500.0);
  Send(Command(2, sim_.utime(), 2, 600.0));  // a birotor's command: not this vehicle's
  EXPECT_EQ(node_.decode_errors(), 1);
  EXPECT_EQ(node_.count_refusals().mismatch, 1);
  Send(Command(3, sim_.utime(), 3, vehicle_.omega_max_rad_s + 1.0));  // above omega_max
  EXPECT_EQ(node_.rule().counters().out_of_range, 1);
  Send(Command(3, sim_.utime() - 200000, 4, 600.0));  // 0.2 s old, the timeout is 0.1 s
  EXPECT_EQ(node_.rule().counters().stale, 1);
  Step(1);
  EXPECT_DOUBLE_EQ(sim_.input().omega_cmd_rad_s[0], 500.0);  // the last good command holds
  Step(400);                                                 // 0.1 s without a good command
  EXPECT_TRUE(node_.rule().timed_out());
  EXPECT_EQ(node_.rule().timeouts(), 1);
  EXPECT_DOUBLE_EQ(sim_.input().omega_cmd_rad_s[1], 0.0);
}

}  // namespace
}  // namespace birotor
