// libFuzzer harness for the flight controller's input path: a byte string
// becomes a stream of POSE, IMU and FORCE packets (raw bytes through the
// checked decoder, or messages whose fields are plausible, hostile (NaN,
// +-Inf, huge) or any bit pattern, with stamps in order, repeated, out of
// order or wild) and control periods at fuzzed host times, fed to
// ControllerService. Every MOTOR_COMMAND it publishes must decode, be finite
// and lie within [0, omega_max]; nothing may crash or trip a sanitizer.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "birotor/force_estimate_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/motor_command_t.hpp"
#include "birotor/pose_t.hpp"
#include "fuzz/datagram_input.h"
#include "fuzz/motor_command_check.h"
#include "nodes/controller_service.h"
#include "transport/lcm_codec.h"

namespace {

constexpr int kMaxOperations = 4096;

// The byte reader of fuzz/datagram_input.h with hostile fields and stamps.
struct Input : birotor::fuzz::ByteReader {
  // Near nominal (scale: the spread), or hostile.
  double Field(double nominal, double scale) {
    const uint8_t kind = Byte();
    if (kind < 200) return nominal + scale * (static_cast<int8_t>(Byte()) / 128.0);
    switch (kind % 5) {
      case 0:
        return std::numeric_limits<double>::quiet_NaN();
      case 1:
        return std::numeric_limits<double>::infinity();
      case 2:
        return -std::numeric_limits<double>::max();
      case 3:
        return nominal * static_cast<int8_t>(Byte());
      default:
        return AnyDouble();
    }
  }
  // Mostly the next period; sometimes repeated, back in time or wild.
  int64_t Stamp(int64_t* clock_us, int64_t period_us) {
    const uint8_t kind = Byte();
    if (kind < 200) {
      *clock_us += period_us;
    } else if (kind < 230) {
      *clock_us -= period_us * (Byte() % 8);
    } else {
      uint64_t bits = 0;
      for (int i = 0; i < 8; ++i) bits = (bits << 8) | Byte();
      return static_cast<int64_t>(bits);
    }
    return *clock_us;
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const birotor::ControllerConfig config;
  const birotor::ChannelNames channels = birotor::MakeChannelNames();
  birotor::fuzz::MotorCommandCheck sink(channels.motor_command, config.vehicle.omega_max_rad_s);
  int64_t clock_us = 0, host_us = 0;
  // The node's own clock reads the fuzzed host time (its one way in stamps
  // each packet with it).
  birotor::ControllerService service(config, channels, &sink, [&host_us] { return host_us; });
  const std::string* routes[3] = {&channels.pose, &channels.imu, &channels.force};
  Input in{{data, size}};
  std::vector<uint8_t> packet;
  for (int op = 0; op < kMaxOperations && in.offset < in.size; ++op) {
    const uint8_t kind = in.Byte();
    host_us += in.Byte() * 50;  // 0 to 12.75 ms between events
    switch (kind % 5) {
      case 0: {
        birotor::pose_t m{};
        m.utime = in.Stamp(&clock_us, 1000);
        m.x_m = in.Field(0.0, 0.5);
        m.z_m = in.Field(0.0, 0.5);
        m.phi_rad = in.Field(0.0, 0.2);
        birotor::EncodeMessage(m, &packet);
        service.HandlePacket(channels.pose, packet.data(), packet.size(), -1);
        break;
      }
      case 1: {
        birotor::imu_t m{};
        m.utime = in.Stamp(&clock_us, 1000);
        m.gyro_y_rad_s = in.Field(0.0, 2.0);
        m.accel_x_m_s2 = in.Field(0.0, 5.0);
        m.accel_z_m_s2 = in.Field(9.81, 5.0);
        birotor::EncodeMessage(m, &packet);
        service.HandlePacket(channels.imu, packet.data(), packet.size(), -1);
        break;
      }
      case 2: {
        birotor::force_estimate_t m{};
        m.utime = in.Stamp(&clock_us, 1000);
        m.status = in.Byte() % 4 == 0 ? static_cast<int32_t>(in.Byte()) : 1;
        for (int i = 0; i < 2; ++i) {
          m.force_n[i] = in.Field(22.0, 10.0);
          m.force_std_n[i] = in.Field(0.1, 0.1);
          m.thrust_scale[i] = in.Field(1.0, 0.5);
        }
        birotor::EncodeMessage(m, &packet);
        service.HandlePacket(channels.force, packet.data(), packet.size(), -1);
        break;
      }
      case 3: {  // raw bytes on any input
        const size_t length = in.Byte();
        packet.assign(length, 0);
        for (uint8_t& b : packet) b = in.Byte();
        service.HandlePacket(*routes[in.Byte() % 3], packet.data(), packet.size(), -1);
        break;
      }
      default:
        service.RunIfDue(host_us);
        break;
    }
  }
  service.PublishStatus(0, host_us);
  return 0;
}
