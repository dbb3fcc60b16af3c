// libFuzzer harness for the estimator's input path: a byte string becomes a
// stream of packets on STRAIN, MOTOR, IMU and POSE (raw bytes through the
// checked decoder, or structured samples whose fields may be NaN, +-Inf, huge,
// negative or jumping backwards in time), fed to EstimatorPipeline with any
// of the three methods. No estimate may carry a non-finite number, no status
// bit outside the documented set, no counter may go backwards, nothing may
// crash, leak or trip a sanitizer.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "birotor/imu_t.hpp"
#include "birotor/motor_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/strain_t.hpp"
#include "estimator/estimator_pipeline.h"
#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace {

using birotor::EstimatorPipeline;
using birotor::InputChannel;

// Every bit of force_estimate_t.status (lcmtypes/force_estimate_t.lcm).
constexpr int32_t kKnownStatusBits = 2047;  // STATUS_VALID .. STATUS_MODEL_MISMATCH
// Reference hover (shared/spec/reference-vehicle.md).
constexpr double kHoverDeflectionRad = 0.0018664;
constexpr double kHoverOmegaRadS = 698.55;
constexpr int64_t kStrainPeriodUs = 1000;
// Upper bounds per input, so one input stays fast (~ms even under ASan):
// packets, and clean samples from bursts (the EKF converges within ~10).
constexpr int kMaxPackets = 4096;
constexpr int kMaxBurstSamples = 256;

// Reads the fuzz input front to back; past the end it yields zeros.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  bool empty() const { return offset_ >= size_; }
  uint8_t Byte() { return offset_ < size_ ? data_[offset_++] : 0; }
  uint64_t Bits64() {
    uint64_t value = 0;
    for (int i = 0; i < 8; ++i) value = (value << 8) | Byte();
    return value;
  }
  // Up to max_size bytes of the input, in place.
  const uint8_t* Take(size_t max_size, size_t* size) {
    const size_t left = size_ - (offset_ < size_ ? offset_ : size_);
    *size = max_size < left ? max_size : left;
    const uint8_t* begin = data_ + offset_;
    offset_ += *size;
    return begin;
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t offset_ = 0;
};

// A field value: mostly near `nominal` (so the filter runs on plausible data
// and reaches deep states), sometimes hostile.
double FieldValue(ByteReader* in, double nominal, double scale) {
  const uint8_t kind = in->Byte();
  switch (kind % 12) {
    case 0:
      return std::numeric_limits<double>::quiet_NaN();
    case 1:
      return std::numeric_limits<double>::infinity();
    case 2:
      return -std::numeric_limits<double>::infinity();
    case 3:
      return std::numeric_limits<double>::max();
    case 4:
      return -std::numeric_limits<double>::denorm_min();
    case 5: {  // any bit pattern
      const uint64_t bits = in->Bits64();
      double value;
      std::memcpy(&value, &bits, sizeof value);
      return value;
    }
    case 6:
      return -nominal;
    case 7:
      return nominal * (static_cast<int8_t>(in->Byte()) / 8.0);  // up to 16x off
    default:
      return nominal + scale * (static_cast<int8_t>(in->Byte()) / 128.0);
  }
}

// a + b with two's-complement wrap-around (no signed-overflow UB in the harness).
int64_t WrapAdd(int64_t a, int64_t b) {
  return static_cast<int64_t>(static_cast<uint64_t>(a) + static_cast<uint64_t>(b));
}

// Sample time: usually the next period of the channel, sometimes a duplicate,
// an out-of-order sample, a gap, a jump backwards, a negative or a huge stamp.
int64_t NextUtime(ByteReader* in, int64_t* clock_us, int64_t period_us) {
  const uint8_t kind = in->Byte();
  switch (kind % 16) {
    case 0:
      break;  // duplicate
    case 1:
      *clock_us = WrapAdd(*clock_us, -period_us * (1 + in->Byte()));
      break;  // out of order
    case 2:
      *clock_us = WrapAdd(*clock_us, 1000 * period_us * (1 + in->Byte()));
      break;  // gap
    case 3:
      *clock_us = WrapAdd(*clock_us, -1000000LL * (1 + in->Byte()));
      break;  // backwards
    case 4:
      *clock_us = -static_cast<int64_t>(in->Bits64() >> 1);
      break;
    case 5:
      *clock_us = std::numeric_limits<int64_t>::max() - in->Byte();
      break;
    case 6:
      *clock_us = std::numeric_limits<int64_t>::min() + in->Byte();
      break;
    case 7:
      *clock_us = static_cast<int64_t>(in->Bits64());
      break;
    case 8:
      *clock_us = WrapAdd(*clock_us, in->Byte());
      break;  // jitter
    default:
      *clock_us = WrapAdd(*clock_us, period_us);
      break;
  }
  return *clock_us;
}

int32_t NextSeq(ByteReader* in, int32_t* seq) {
  const uint8_t kind = in->Byte();
  if (kind % 8 == 0)
    *seq = static_cast<int32_t>(in->Bits64());  // anything, incl. wrap
  else if (kind % 8 == 1)
    *seq = static_cast<int32_t>(static_cast<uint32_t>(*seq) + 1u + in->Byte());  // gap
  else
    *seq = static_cast<int32_t>(static_cast<uint32_t>(*seq) + 1u);  // wraps
  return *seq;
}

void CheckEstimate(const birotor::ForceEstimate& estimate) {
  for (int i = 0; i < 2; ++i) {
    if (!std::isfinite(estimate.force_n[i]) || !std::isfinite(estimate.force_std_n[i]) ||
        !std::isfinite(estimate.thrust_scale[i]) || estimate.force_std_n[i] < 0) {
      std::abort();
    }
  }
  if ((estimate.status & ~kKnownStatusBits) != 0) std::abort();
  // VALID is never set with INPUT_STALE or INPUT_CONFLICT (force_estimate_t.lcm).
  if ((estimate.status & birotor::kStatusValid) &&
      (estimate.status & (birotor::kStatusInputStale | birotor::kStatusInputConflict))) {
    std::abort();
  }
}

// Counters only ever grow; an accepted sample never exceeds what was received.
void CheckHealth(const birotor::PipelineHealth& health, const int64_t (&received)[birotor::kNumInputChannels]) {
  for (int i = 0; i < birotor::kNumInputChannels; ++i) {
    const birotor::InputCounters& c = health.inputs[i];
    if (c.received != received[i] || c.fused < 0 || c.fused > c.received) std::abort();
    // One fusion report at most per accepted sample.
    if (c.fused + c.rejected_gate + c.not_fused > c.received) std::abort();
    if (c.gaps < 0 || c.missing_samples < 0 || c.gaps > c.missing_samples) std::abort();
  }
  if (health.resets < 0 || health.published < 0) std::abort();
}

// Raw bytes of one channel through the checked decoder, as the daemon does.
template <class Msg>
bool DecodeRaw(ByteReader* in, Msg* message) {
  size_t size = 0;
  const uint8_t* bytes = in->Take(in->Byte(), &size);
  // Half the time put the right fingerprint in front so the fields get fuzzed.
  if (in->Byte() % 2 == 0 && size >= 8) {
    uint8_t packet[256];
    std::memcpy(packet, bytes, size);
    const uint64_t hash = static_cast<uint64_t>(Msg::getHash());
    for (int i = 0; i < 8; ++i) packet[i] = static_cast<uint8_t>(hash >> (56 - 8 * i));
    return birotor::DecodeMessage(packet, size, message) == birotor::DecodeError::kNone;
  }
  return birotor::DecodeMessage(bytes, size, message) == birotor::DecodeError::kNone;
}

// A channel's synthetic stream: its last stamp, period and seq.
struct ChannelClock {
  int64_t* clock_us;  // last stamp of the channel [us]
  int64_t period_us;
  int32_t* seq;  // last seq of the channel
};

// The next sample of a channel: 1 in 8 packets raw bytes through the checked
// decoder (a decode error is counted, as the daemon does, and false
// returned), the others stamped and numbered on the channel's clock and
// filled by `make` from the fuzzer's bytes.
template <class Msg, class Sample, class Make>
bool NextSample(ByteReader* in, bool raw, InputChannel channel, const ChannelClock& clock, EstimatorPipeline* pipeline,
                Make make, Sample* sample) {
  if (!raw) {
    sample->utime = NextUtime(in, clock.clock_us, clock.period_us);
    sample->seq = NextSeq(in, clock.seq);
    make(sample);
    return true;
  }
  Msg message;
  if (!DecodeRaw(in, &message)) {
    pipeline->CountDecodeError(channel);
    return false;
  }
  *sample = birotor::FromMessage(message);
  return true;
}

// count identical well-formed hover STRAIN samples, with a MOTOR sample at
// every second one, on the channels' clocks and seq counters (index 0: STRAIN,
// 1: MOTOR), counted in received.
void FeedHoverBurst(int count, int64_t* clock_us, int32_t* seq, int64_t* received, EstimatorPipeline* pipeline,
                    birotor::ForceEstimate* estimate) {
  for (int k = 0; k < count; ++k) {
    birotor::StrainSample s;
    clock_us[0] = WrapAdd(clock_us[0], kStrainPeriodUs);
    s.utime = clock_us[0];
    s.seq = seq[0] = static_cast<int32_t>(static_cast<uint32_t>(seq[0]) + 1u);
    s.deflection_rad[0] = -kHoverDeflectionRad;
    s.deflection_rad[1] = kHoverDeflectionRad;
    if (k % 2 == 0) {
      birotor::MotorSample m;
      clock_us[1] = clock_us[0];
      m.utime = clock_us[1];
      m.seq = seq[1] = static_cast<int32_t>(static_cast<uint32_t>(seq[1]) + 1u);
      m.omega_cmd_rad_s[0] = m.omega_cmd_rad_s[1] = kHoverOmegaRadS;
      m.omega_meas_rad_s[0] = m.omega_meas_rad_s[1] = kHoverOmegaRadS;
      pipeline->CountReceived(InputChannel::kMotor);
      ++received[1];
      pipeline->OnMotor(m);
    }
    pipeline->CountReceived(InputChannel::kStrain);
    ++received[0];
    if (pipeline->OnStrain(s, estimate)) CheckEstimate(*estimate);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  ByteReader in(data, size);
  birotor::EstimatorConfig config;
  const uint8_t method = in.Byte();
  const std::vector<std::string>& methods = birotor::EstimationMethodNames();
  config.method = methods[method % methods.size()];
  EstimatorPipeline pipeline(config);

  int64_t clock_us[birotor::kNumInputChannels] = {0, 0, 0, 0};
  int32_t seq[birotor::kNumInputChannels] = {0, 0, 0, 0};
  int64_t received[birotor::kNumInputChannels] = {0, 0, 0, 0};
  const int64_t period_us[birotor::kNumInputChannels] = {kStrainPeriodUs, 2 * kStrainPeriodUs, kStrainPeriodUs,
                                                         10 * kStrainPeriodUs};
  birotor::ForceEstimate estimate;

  int burst_samples = 0;
  for (int packet = 0; packet < kMaxPackets && !in.empty(); ++packet) {
    const uint8_t header = in.Byte();
    const int channel_index = header % birotor::kNumInputChannels;
    const InputChannel channel = static_cast<InputChannel>(channel_index);
    const bool raw = (header / birotor::kNumInputChannels) % 8 == 0;  // 1 in 8 packets raw
    // A run of identical well-formed strain+motor samples lets the filter
    // converge cheaply (a byte buys up to 255 samples).
    const bool burst = (header / birotor::kNumInputChannels) % 8 == 1;
    if (burst) {
      const int count = std::min<int>(in.Byte(), kMaxBurstSamples - burst_samples);
      burst_samples += count;
      FeedHoverBurst(count, clock_us, seq, received, &pipeline, &estimate);
      continue;
    }
    pipeline.CountReceived(channel);
    ++received[channel_index];

    const ChannelClock clock{&clock_us[channel_index], period_us[channel_index], &seq[channel_index]};
    switch (channel) {
      case InputChannel::kStrain: {
        birotor::StrainSample s;
        const auto make = [&](birotor::StrainSample* x) {
          x->deflection_rad[0] = FieldValue(&in, -kHoverDeflectionRad, 1e-3);
          x->deflection_rad[1] = FieldValue(&in, kHoverDeflectionRad, 1e-3);
        };
        if (NextSample<birotor::strain_t>(&in, raw, channel, clock, &pipeline, make, &s) &&
            pipeline.OnStrain(s, &estimate)) {
          CheckEstimate(estimate);
        }
        break;
      }
      case InputChannel::kMotor: {
        birotor::MotorSample m;
        const auto make = [&](birotor::MotorSample* x) {
          for (int i = 0; i < 2; ++i) x->omega_cmd_rad_s[i] = FieldValue(&in, kHoverOmegaRadS, 200.0);
          for (int i = 0; i < 2; ++i) x->omega_meas_rad_s[i] = FieldValue(&in, kHoverOmegaRadS, 200.0);
        };
        if (NextSample<birotor::motor_t>(&in, raw, channel, clock, &pipeline, make, &m)) pipeline.OnMotor(m);
        break;
      }
      case InputChannel::kImu: {
        birotor::ImuSample s;
        const auto make = [&](birotor::ImuSample* x) {
          x->gyro_y_rad_s = FieldValue(&in, 0.0, 1.0);
          x->accel_x_m_s2 = FieldValue(&in, 0.0, 1.0);
          x->accel_z_m_s2 = FieldValue(&in, 9.81, 1.0);
        };
        if (NextSample<birotor::imu_t>(&in, raw, channel, clock, &pipeline, make, &s)) pipeline.OnImu(s);
        break;
      }
      case InputChannel::kPose: {
        birotor::PoseSample s;
        const auto make = [&](birotor::PoseSample* x) {
          x->x_m = FieldValue(&in, 0.0, 1.0);
          x->z_m = FieldValue(&in, 0.0, 1.0);
          x->phi_rad = FieldValue(&in, 0.0, 0.3);
        };
        if (NextSample<birotor::pose_t>(&in, raw, channel, clock, &pipeline, make, &s)) pipeline.OnPose(s);
        break;
      }
    }
    if (packet % 64 == 0) pipeline.TakePeriod();
  }
  CheckHealth(pipeline.health(), received);
  if (pipeline.health().published > 0) CheckEstimate(pipeline.health().last_estimate);
  return 0;
}
