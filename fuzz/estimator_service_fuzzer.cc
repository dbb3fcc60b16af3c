// libFuzzer harness for the daemon's packet handler: raw byte strings on
// every channel of its route table (STRAIN, MOTOR, IMU, POSE, STRAIN_N,
// MOTOR_N, its own FORCE) go through EstimatorService::HandlePacket(channel,
// ...) (its one way in, the PacketHandler entry its message source calls),
// interleaved with ESTIMATOR_STATUS publication.
// Every FORCE, ESTIMATOR_STATUS and ESTIMATOR_LEARNED_N it publishes must
// decode and carry only finite forces (and learned values for both arms:
// the birotor's gauges, tip masses and body mass always have one); nothing
// may crash, leak or trip a sanitizer.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "birotor/estimator_learned_n_t.hpp"
#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/motor_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/strain_t.hpp"
#include "nodes/estimator_service.h"
#include "transport/host_clock.h"
#include "transport/lcm_codec.h"

namespace {

constexpr double kHoverDeflectionRad = 0.0018664;  // shared/spec/reference-vehicle.md
constexpr double kHoverOmegaRadS = 698.55;
// Upper bounds per input, so one input stays fast (~ms even under ASan).
constexpr int kMaxPackets = 2048;
constexpr int kMaxBurstSamples = 256;

// Decodes and checks everything the service publishes.
class CheckingSink : public birotor::MessageSink {
 public:
  explicit CheckingSink(const birotor::ChannelNames& channels) : channels_(channels) {}
  void Publish(const std::string& channel, int64_t /*timestamp_us*/, const void* data, size_t size) override {
    if (channel == channels_.force) {
      if (birotor::DecodeMessage(data, size, &force_) != birotor::DecodeError::kNone) std::abort();
      for (int i = 0; i < 2; ++i) {
        if (!std::isfinite(force_.force_n[i]) || !std::isfinite(force_.force_std_n[i]) ||
            !std::isfinite(force_.thrust_scale[i])) {
          std::abort();
        }
      }
    } else if (channel == channels_.estimator_status) {
      if (birotor::DecodeMessage(data, size, &status_) != birotor::DecodeError::kNone) std::abort();
      if (status_.num_inputs != static_cast<int32_t>(status_.inputs.size())) std::abort();
    } else if (channel == channels_.estimator_learned_n) {
      if (birotor::DecodeMessage(data, size, &learned_) != birotor::DecodeError::kNone) std::abort();
      if (learned_.n_arms != 2 || learned_.seq != status_.seq || learned_.utime != status_.utime) std::abort();
      for (size_t i = 0; i < 2; ++i) {
        if (!std::isfinite(learned_.strain_scale[i]) || !std::isfinite(learned_.tip_mass_kg[i]) ||
            !std::isfinite(learned_.strain_noise_rad[i])) {
          std::abort();
        }
      }
      if (!std::isfinite(learned_.body_mass_kg)) std::abort();
    } else {
      std::abort();  // the service publishes nothing else
    }
  }

 private:
  birotor::ChannelNames channels_;
  birotor::force_estimate_t force_;
  birotor::estimator_status_t status_;
  birotor::estimator_learned_n_t learned_;
};

template <class Msg>
void WriteFingerprint(uint8_t* packet) {
  const uint64_t hash = static_cast<uint64_t>(Msg::getHash());
  for (int i = 0; i < 8; ++i) packet[i] = static_cast<uint8_t>(hash >> (56 - 8 * i));
}

void SetFingerprint(birotor::InputChannel channel, uint8_t* packet) {
  switch (channel) {
    case birotor::InputChannel::kStrain:
      WriteFingerprint<birotor::strain_t>(packet);
      break;
    case birotor::InputChannel::kMotor:
      WriteFingerprint<birotor::motor_t>(packet);
      break;
    case birotor::InputChannel::kImu:
      WriteFingerprint<birotor::imu_t>(packet);
      break;
    case birotor::InputChannel::kPose:
      WriteFingerprint<birotor::pose_t>(packet);
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool quiet = [] {
    spdlog::set_level(spdlog::level::off);  // decode warnings would flood the fuzzer's output
    return true;
  }();
  (void)quiet;
  const birotor::ChannelNames channels = birotor::MakeChannelNames("FUZZ_");
  CheckingSink sink(channels);
  birotor::EstimatorConfig config;
  birotor::EstimatorServiceOptions options;
  options.report_processing_time = (size % 2) == 0;
  birotor::EstimatorService service(config, channels, options, &sink);
  // STRAIN, MOTOR, IMU, POSE (InputChannel's order), STRAIN_N, MOTOR_N, FORCE.
  const std::vector<std::string> names = service.InputChannels();

  // Well-formed hover packets, to reach the filter's deeper states.
  birotor::strain_t strain{};
  birotor::motor_t motor{};
  std::vector<uint8_t> buffer;
  int64_t utime = 1000000;
  int32_t seq = 0;

  int burst_samples = 0;
  size_t offset = 0;
  for (int packet = 0; packet < kMaxPackets && offset < size; ++packet) {
    const uint8_t header = data[offset++];
    const size_t route = header % names.size();
    const int kind = static_cast<int>((header / names.size()) % 8);
    if (kind == 0) {  // hover burst: strain at 1 kHz, motor at 500 Hz
      const int count = std::min<int>(offset < size ? data[offset++] : 0, kMaxBurstSamples - burst_samples);
      burst_samples += count;
      for (int k = 0; k < count; ++k) {
        utime += 1000;
        strain.utime = utime;
        strain.seq = seq;
        strain.deflection_rad[0] = -kHoverDeflectionRad;
        strain.deflection_rad[1] = kHoverDeflectionRad;
        if (seq % 2 == 0) {
          motor.utime = utime;
          motor.seq = seq / 2;
          for (int i = 0; i < 2; ++i) motor.omega_cmd_rad_s[i] = motor.omega_meas_rad_s[i] = kHoverOmegaRadS;
          birotor::EncodeMessage(motor, &buffer);
          service.HandlePacket(channels.motor, buffer.data(), buffer.size(), -1);
        }
        ++seq;
        birotor::EncodeMessage(strain, &buffer);
        service.HandlePacket(channels.strain, buffer.data(), buffer.size(), -1);
      }
      continue;
    }
    if (kind == 1) {  // status message, as the daemon's timer does
      service.PublishStatus(birotor::WallClockUs(), 0.2);
      continue;
    }
    // A raw packet of up to 255 bytes; kinds 2-4 get the right fingerprint so
    // the fields (utime, seq, values) are what the fuzzer varies.
    const size_t length = offset < size ? data[offset++] : 0;
    uint8_t raw[256];
    const size_t available = length < size - offset ? length : size - offset;
    std::memcpy(raw, data + offset, available);
    offset += available;
    if (kind <= 4 && available >= 8 && route < birotor::kNumInputChannels) {
      SetFingerprint(static_cast<birotor::InputChannel>(route), raw);
    }
    // kind 7: an old packet as seen live (receive time one second ago): overload drop path.
    const int64_t receive_wall_utime = kind == 7 ? birotor::WallClockUs() - 1000000 : -1;
    // Through the PacketHandler entry a message source calls (by channel name).
    service.HandlePacket(names[route], raw, available, receive_wall_utime);
  }
  service.PublishStatus(birotor::WallClockUs(), 0.2);
  return 0;
}
