// Decoding and bookkeeping of birotor-monitor.
#include "monitor/monitor_collector.h"

#include <algorithm>
#include <cmath>

#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

// TRUTH and FORCE arrive at 1 kHz (interface.md); 20 % head room.
constexpr double kSamplesPerSecond = 1200.0;
// A utime step longer than this many truth periods means lost TRUTH packets.
constexpr double kTruthGapPeriods = 1.5;

}  // namespace

MonitorCollector::MonitorCollector(const ChannelNames& channels, double expected_duration_s) : channels_(channels) {
  const size_t capacity = static_cast<size_t>(std::max(1.0, expected_duration_s) * kSamplesPerSecond);
  forces_.reserve(capacity);
  truth_.reserve(capacity);
  fault_utimes_.reserve(1024);
}

void MonitorCollector::HandlePacket(const std::string& channel, const void* data, size_t size) {
  if (channel == channels_.force) {
    if (DecodeMessage(data, size, &force_message_) == DecodeError::kNone) {
      OnForce(FromMessage(force_message_));
    } else {
      ++decode_errors_;
    }
  } else if (channel == channels_.truth) {
    if (DecodeMessage(data, size, &truth_message_) == DecodeError::kNone) {
      OnTruth(FromMessage(truth_message_));
    } else {
      ++decode_errors_;
    }
  } else if (channel == channels_.estimator_status) {
    if (DecodeMessage(data, size, &status_message_) == DecodeError::kNone) {
      OnStatus(status_message_);
    } else {
      ++decode_errors_;
    }
  }
}

void MonitorCollector::OnForce(const ForceEstimate& estimate) {
  // seq wraps as int32 (interface.md); unsigned arithmetic keeps the wrap a +1 step.
  const bool seq_jump =
      !forces_.empty() && static_cast<uint32_t>(estimate.seq) - static_cast<uint32_t>(forces_.back().seq) != 1u;
  if (seq_jump || (estimate.status & kStatusFilterReset)) fault_utimes_.push_back(estimate.utime);
  forces_.push_back(estimate);
}

void MonitorCollector::OnTruth(const TruthSample& sample) {
  if (!truth_.empty()) {
    const int64_t step_us = sample.utime - truth_.back().utime;
    if (step_us > 0 && (truth_period_us_ == 0 || step_us < truth_period_us_)) truth_period_us_ = step_us;
    if (truth_period_us_ > 0 && static_cast<double>(step_us) > kTruthGapPeriods * truth_period_us_) {
      ++truth_gaps_;
    }
  }
  truth_.push_back(sample);
}

void MonitorCollector::OnStatus(const estimator_status_t& status) {
  ++status_messages_;
  health_.received = true;
  health_.method = status.method;
  health_.resets = status.resets;
  health_.processing_time_p99_us = status.processing_time_p99_us;
  // inputs[] are STRAIN, MOTOR, IMU, POSE in this order (estimator_status_t.lcm).
  for (const input_health_t& input : status.inputs) {
    if (input.channel != kStrainChannel) continue;
    health_.strain_received = input.received;
    health_.strain_fused = input.fused;
    health_.strain_faults =
        input.gaps + input.out_of_order + input.duplicates + input.rejected_invalid + input.decode_errors;
    health_.dropped_overload = input.dropped_overload;
  }
}

EvalResult MonitorCollector::Evaluate(const EvalOptions& options) const {
  return birotor::Evaluate(forces_, truth_, fault_utimes_, options);
}

}  // namespace birotor
