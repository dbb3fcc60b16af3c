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
  routes_.Add(channels_.truth, MonitorChannel::kTruth);
  routes_.Add(channels_.force, MonitorChannel::kForce);
  routes_.Add(channels_.estimator_status, MonitorChannel::kEstimatorStatus);
}

void MonitorCollector::HandlePacket(std::string_view channel, const void* data, size_t size,
                                    int64_t /*receive_wall_utime*/) {
  MonitorChannel routed;
  if (!routes_.Find(channel, &routed)) return;
  switch (routed) {
    case MonitorChannel::kForce:
      if (DecodeMessage(data, size, &force_message_) != DecodeError::kNone) break;
      OnForce(FromMessage(force_message_));
      return;
    case MonitorChannel::kTruth:
      if (DecodeMessage(data, size, &truth_message_) != DecodeError::kNone) break;
      OnTruth(FromMessage(truth_message_));
      return;
    case MonitorChannel::kEstimatorStatus:
      if (DecodeMessage(data, size, &status_message_) != DecodeError::kNone) break;
      OnStatus(status_message_);
      return;
  }
  ++decode_errors_;
}

void MonitorCollector::OnForce(const ForceEstimate& estimate) {
  const bool first = forces_.empty();
  // seq wraps as int32 (interface.md); unsigned arithmetic keeps the wrap a +1 step.
  const uint32_t seq_step =
      first ? 1u : static_cast<uint32_t>(estimate.seq) - static_cast<uint32_t>(forces_.back().seq);
  const bool seq_jump = seq_step != 1u;
  if (seq_jump || (estimate.status & kStatusFilterReset)) fault_utimes_.push_back(estimate.utime);
  if (seq_jump && seq_step < 0x80000000u) {
    ++force_stats_.seq_gaps;
    force_stats_.seq_missing += seq_step - 1;
  } else if (seq_jump) {
    ++force_stats_.seq_backwards;
  }
  if (!first && (estimate.status & kStatusFilterReset)) ++force_stats_.resets_after_start;
  if (estimate.status & kStatusValid) ++force_stats_.valid;
  bool finite = true;
  for (int r = 0; r < 2; ++r) {
    finite = finite && std::isfinite(estimate.force_n[r]) && std::isfinite(estimate.force_std_n[r]) &&
             std::isfinite(estimate.thrust_scale[r]);
  }
  if (!finite) ++force_stats_.nonfinite;
  const uint32_t previous_status =
      first ? static_cast<uint32_t>(estimate.status) : static_cast<uint32_t>(forces_.back().status);
  const uint32_t risen = static_cast<uint32_t>(estimate.status) & ~previous_status;
  for (int bit = 0; bit < 32; ++bit) {
    if (!(risen & (1u << bit))) continue;
    FlagRises& r = rises_[bit];
    if (r.count++ == 0) r.first_utime = estimate.utime;
    r.last_utime = estimate.utime;
  }
  forces_.push_back(estimate);
}

const FlagRises& MonitorCollector::rises(int32_t bit) const {
  static const FlagRises kNone;
  for (int position = 0; position < 32; ++position) {
    if (static_cast<uint32_t>(bit) == (1u << position)) return rises_[position];
  }
  return kNone;
}

const input_health_t* MonitorCollector::input(const std::string& channel) const {
  for (const input_health_t& input : latest_status_.inputs) {
    if (input.channel == channel) return &input;
  }
  return nullptr;
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
  latest_status_ = status;
  if (std::isfinite(status.strain_nis_mean)) {  // NaN: no strain sample in the period
    strain_nis_sum_ += status.strain_nis_mean;
    ++strain_nis_reports_;
  }
  if (std::isfinite(status.strain_nis_max) && !(status.strain_nis_max <= strain_nis_max_)) {
    strain_nis_max_ = status.strain_nis_max;
  }
}

double MonitorCollector::strain_nis_mean_over_run() const {
  return strain_nis_reports_ > 0 ? strain_nis_sum_ / static_cast<double>(strain_nis_reports_)
                                 : std::numeric_limits<double>::quiet_NaN();
}

EvalResult MonitorCollector::Evaluate(const EvalOptions& options) const {
  return birotor::Evaluate(forces_, truth_, fault_utimes_, options);
}

}  // namespace birotor
