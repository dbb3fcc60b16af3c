// libFuzzer harness for the flight controller's receive path (issue 23): the
// input is a stream of UDP datagrams (fuzz/datagram_input.h: raw, LC02 or
// LC03 around its channels or garbage names, and well-formed POSE, IMU and
// FORCE with fuzzed fields), each parsed by the daemons' LC02 parser and
// routed by the udpm source into ControllerService::HandlePacket(channel,
// ...), the entry the live controller runs, with timer periods and status in
// between. Every MOTOR_COMMAND must decode, be finite and within [0,
// omega_max]; nothing may crash, leak or trip a sanitizer.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "birotor/force_estimate_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/pose_t.hpp"
#include "fuzz/datagram_input.h"
#include "fuzz/motor_command_check.h"
#include "nodes/controller_service.h"
#include "transport/host_clock.h"
#include "transport/lcm_codec.h"

namespace {

constexpr int kMaxDatagrams = 2048;

// A well-formed message for channel index i (POSE, IMU, FORCE) with fields
// from the input: stamps near a running clock or wild, values any bit pattern.
std::vector<uint8_t> Message(size_t i, birotor::fuzz::ByteReader* in, int64_t* clock_us) {
  // Wrapping addition: a wild step may overflow int64_t without undefined behaviour.
  const uint64_t step_us = in->Byte() < 220 ? 1000 : static_cast<uint64_t>(in->AnyInt64());
  *clock_us = static_cast<int64_t>(static_cast<uint64_t>(*clock_us) + step_us);
  std::vector<uint8_t> bytes;
  if (i % 3 == 0) {
    birotor::pose_t m{};
    m.utime = *clock_us;
    m.seq = in->Byte();
    m.x_m = in->Byte() < 128 ? 0.0 : in->AnyDouble();
    m.z_m = in->Byte() < 128 ? 0.0 : in->AnyDouble();
    m.phi_rad = in->Byte() < 128 ? 0.0 : in->AnyDouble();
    birotor::EncodeMessage(m, &bytes);
  } else if (i % 3 == 1) {
    birotor::imu_t m{};
    m.utime = *clock_us;
    m.seq = in->Byte();
    m.gyro_y_rad_s = in->Byte() < 128 ? 0.0 : in->AnyDouble();
    m.accel_z_m_s2 = in->Byte() < 128 ? 9.81 : in->AnyDouble();
    birotor::EncodeMessage(m, &bytes);
  } else {
    birotor::force_estimate_t m{};
    m.utime = *clock_us;
    m.seq = in->Byte();
    m.status = in->Byte() < 200 ? 1 : in->Byte();
    for (int r = 0; r < 2; ++r) {
      m.force_n[r] = in->Byte() < 128 ? 22.0 : in->AnyDouble();
      m.force_std_n[r] = in->Byte() < 128 ? 0.1 : in->AnyDouble();
      m.thrust_scale[r] = in->Byte() < 128 ? 1.0 : in->AnyDouble();
    }
    birotor::EncodeMessage(m, &bytes);
  }
  return bytes;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const birotor::ControllerConfig config;
  const birotor::ChannelNames channels = birotor::MakeChannelNames("FUZZ_");
  birotor::fuzz::MotorCommandCheck sink(channels.motor_command, config.vehicle.omega_max_rad_s);
  birotor::ControllerService service(config, channels, &sink);
  const std::vector<std::string> subscribed = service.InputChannels();
  birotor::fuzz::ByteReader in{data, size};
  int64_t clock_us = 1000000;
  for (int k = 0; k < kMaxDatagrams && !in.done(); ++k) {
    const uint8_t action = in.Byte();
    if (action % 8 == 7) {  // the loop's periodic work
      service.RunIfDue(birotor::SteadyClockUs() + in.Byte() * 1000);
      continue;
    }
    const std::vector<uint8_t> payload = Message(action, &in, &clock_us);
    birotor::fuzz::Deliver(birotor::fuzz::NextDatagram(&in, subscribed, payload), birotor::WallClockUs(), subscribed,
                           &service);
  }
  service.PublishStatus(0, birotor::SteadyClockUs());
  return 0;
}
