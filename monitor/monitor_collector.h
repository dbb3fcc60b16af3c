// birotor-monitor's bookkeeping, free of any LCM instance: decodes TRUTH, FORCE
// and ESTIMATOR_STATUS packets, keeps the newest of each for the live view and
// every FORCE/TRUTH pair for the final figures, which are computed with
// birotor-eval's own Evaluate() so that the two tools report the same numbers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_t.hpp"
#include "birotor/truth_t.hpp"
#include "estimator/samples.h"
#include "evaluation/eval_metrics.h"
#include "transport/channels.h"

namespace birotor {

// The newest estimator health, reduced to what the view shows.
struct MonitorHealth {
  bool received = false;
  std::string method;           // "ekf", "inversion" or "motor_map"
  int64_t strain_received = 0;  // packets seen by the estimator
  int64_t strain_fused = 0;
  int64_t strain_faults = 0;     // gaps + out of order + duplicates + invalid + decode errors
  int64_t dropped_overload = 0;  // strain packets the estimator shed under load
  int64_t resets = 0;
  double processing_time_p99_us = 0;  // [us]; NaN when not measured
};

class MonitorCollector {
 public:
  // expected_duration_s sizes the sample buffers (1 kHz TRUTH and FORCE), so
  // that a run of that length does not reallocate; longer runs still work.
  MonitorCollector(const ChannelNames& channels, double expected_duration_s);

  // One packet of any channel; other channels are ignored. Never throws; an
  // undecodable packet is counted in decode_errors().
  void HandlePacket(const std::string& channel, const void* data, size_t size);

  // Final figures over everything received, as birotor-eval computes them.
  // Input-fault times are inferred from the FORCE stream (see fault_utimes()).
  EvalResult Evaluate(const EvalOptions& options) const;

  // Vehicle times [us] of FORCE messages that follow a seq discontinuity or
  // carry the filter-reset bit: where the estimator met an input fault.
  // birotor-eval takes them from the estimator's counters instead; the two
  // agree except for a rejected (NaN) sample, which shows here one strain
  // period later, and for a FORCE lost between estimator and monitor.
  const std::vector<int64_t>& fault_utimes() const { return fault_utimes_; }

  const std::vector<ForceEstimate>& forces() const { return forces_; }
  const std::vector<TruthSample>& truth() const { return truth_; }
  bool has_force() const { return !forces_.empty(); }
  bool has_truth() const { return !truth_.empty(); }
  const ForceEstimate& latest_force() const { return forces_.back(); }
  const TruthSample& latest_truth() const { return truth_.back(); }
  const MonitorHealth& health() const { return health_; }
  int64_t decode_errors() const { return decode_errors_; }
  int64_t status_messages() const { return status_messages_; }

  // TRUTH samples whose utime jumped by more than 1.5 truth periods: packets
  // lost on the way to the monitor (the simulator never skips TRUTH).
  int64_t truth_gaps() const { return truth_gaps_; }

 private:
  void OnForce(const ForceEstimate& estimate);
  void OnTruth(const TruthSample& sample);
  void OnStatus(const estimator_status_t& status);

  ChannelNames channels_;
  std::vector<ForceEstimate> forces_;
  std::vector<TruthSample> truth_;
  std::vector<int64_t> fault_utimes_;
  MonitorHealth health_;
  int64_t decode_errors_ = 0;
  int64_t status_messages_ = 0;
  int64_t truth_gaps_ = 0;
  int64_t truth_period_us_ = 0;  // smallest utime step seen between TRUTH samples

  // Decode buffers, reused for every packet.
  force_estimate_t force_message_;
  truth_t truth_message_;
  estimator_status_t status_message_;
};

}  // namespace birotor
