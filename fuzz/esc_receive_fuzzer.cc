// libFuzzer harness for the simulator's receive path as the vehicle's ESCs
// (birotor-sim --external-controller, issue 23): the input is a stream of
// UDP datagrams (fuzz/datagram_input.h: raw, LC02 or LC03 around
// MOTOR_COMMAND or garbage names, and well-formed MOTOR_COMMAND with fuzzed
// speeds and stamps), each parsed by the daemons' LC02 parser and routed by
// the udpm source into EscCommandNode::HandlePacket, with simulator steps in
// between. The simulated state must stay finite with the rotor speeds within
// [0, omega_max]; nothing may crash, leak or trip a sanitizer.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "birotor/motor_command_t.hpp"
#include "fuzz/datagram_input.h"
#include "nodes/esc_command_node.h"
#include "samples/sample_sink.h"
#include "transport/channels.h"
#include "transport/host_clock.h"
#include "transport/lcm_codec.h"

namespace {

constexpr int kMaxDatagrams = 2048;

birotor::Scenario ShortHover() {
  birotor::Scenario scenario;  // the built-in hover (simulator/scenario.h defaults)
  scenario.duration_s = 2.0;
  return scenario;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const birotor::Scenario scenario = ShortHover();
  birotor::Simulator sim(scenario);
  sim.UseExternalCommands(0.1);
  const birotor::ChannelNames channels = birotor::MakeChannelNames("FUZZ_");
  birotor::EscCommandNode node(channels.motor_command, &sim);
  const std::vector<std::string> subscribed = node.InputChannels();
  birotor::SampleSink sink;  // the samples are not looked at
  birotor::fuzz::ByteReader in{data, size};
  birotor::motor_command_t command{};
  std::vector<uint8_t> payload;
  for (int k = 0; k < kMaxDatagrams && !in.done(); ++k) {
    const uint8_t action = in.Byte();
    if (action % 4 == 3) {  // simulator steps, as the live loop between polls
      for (int s = in.Byte() % 16; s >= 0 && !sim.done(); --s) sim.Step(&sink);
      continue;
    }
    command.utime = in.Byte() < 200 ? sim.utime() : in.AnyInt64();
    command.seq = in.Byte();
    for (double& omega : command.omega_cmd_rad_s) omega = in.Byte() < 128 ? 698.55 : in.AnyDouble();
    birotor::EncodeMessage(command, &payload);
    birotor::fuzz::Deliver(birotor::fuzz::NextDatagram(&in, subscribed, payload), birotor::WallClockUs(), subscribed,
                           &node);
  }
  const double omega_max = scenario.vehicle.omega_max_rad_s;
  if (!sim.state().allFinite()) std::abort();
  for (const int index : {birotor::kPlantOmega1, birotor::kPlantOmega2}) {
    const double omega = sim.state()(index);
    if (omega < -1e-9 || omega > omega_max * (1 + 1e-9)) std::abort();
  }
  return 0;
}
