// birotor-monitor's bookkeeping, free of any LCM instance: decodes TRUTH, FORCE
// and ESTIMATOR_STATUS packets, keeps the newest of each for the live view,
// the history of every status bit and of the FORCE seq, and every FORCE/TRUTH
// pair for the final figures, which are computed with birotor-eval's own
// Evaluate() so that the two tools report the same numbers. Without TRUTH (a
// real vehicle) the FORCE and ESTIMATOR_STATUS parts stand alone.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_t.hpp"
#include "birotor/truth_t.hpp"
#include "evaluation/eval_metrics.h"
#include "samples/samples.h"
#include "sources/channel_routes.h"
#include "sources/message_source.h"
#include "transport/channels.h"

namespace birotor {

// Rises of one status bit in the FORCE stream: set on a message after a
// message without it. The first message received is the starting state, not
// a rise (its FILTER_RESET is the estimator's start-up initialisation).
struct FlagRises {
  int64_t count = 0;
  int64_t first_utime = 0;  // vehicle clock [us]; valid when count > 0
  int64_t last_utime = 0;   // the newest rise [us]
};

// The FORCE stream's own bookkeeping, with or without TRUTH.
struct ForceStreamStats {
  int64_t seq_gaps = 0;            // seq jumps forward by more than 1
  int64_t seq_missing = 0;         // messages missing according to seq (sum of the jumps)
  int64_t seq_backwards = 0;       // seq going back (estimator restarted, or reordering)
  int64_t resets_after_start = 0;  // FILTER_RESET on any message but the first (the start-up one)
  int64_t valid = 0;               // messages with VALID
  int64_t nonfinite = 0;           // messages with a NaN/Inf force, std or thrust scale
};

// The channels the collector reads (its route table maps the full names).
enum class MonitorChannel : int { kTruth, kForce, kEstimatorStatus };

class MonitorCollector : public PacketHandler {
 public:
  // expected_duration_s sizes the sample buffers (1 kHz TRUTH and FORCE), so
  // that a run of that length does not reallocate; longer runs still work.
  MonitorCollector(const ChannelNames& channels, double expected_duration_s);

  // PacketHandler, the one way in: one packet of a channel of the route
  // table (TRUTH, FORCE, ESTIMATOR_STATUS); other channels are ignored, the
  // arrival time is not used. Never throws; an undecodable packet is counted
  // in decode_errors().
  void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t receive_wall_utime) override;
  // The channels it reads (the route table's names), to subscribe a source to.
  std::vector<std::string> InputChannels() const { return routes_.Names(); }

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
  int64_t decode_errors() const { return decode_errors_; }
  int64_t status_messages() const { return status_messages_; }

  const ForceStreamStats& force_stats() const { return force_stats_; }
  // Rises of bit (one of the kStatus* constants) in the FORCE stream.
  const FlagRises& rises(int32_t bit) const;
  // The newest ESTIMATOR_STATUS; meaningful when has_status().
  bool has_status() const { return status_messages_ > 0; }
  const estimator_status_t& latest_status() const { return latest_status_; }
  // The newest ESTIMATOR_STATUS counters of one input ("STRAIN", "MOTOR",
  // "IMU", "POSE"); nullptr if it has none.
  const input_health_t* input(const std::string& channel) const;
  // Strain NIS over every ESTIMATOR_STATUS that had strain samples: the mean
  // of the reported period means and the largest period max (NaN if none).
  double strain_nis_mean_over_run() const;
  double strain_nis_max_over_run() const { return strain_nis_max_; }

  // TRUTH samples whose utime jumped by more than 1.5 truth periods: packets
  // lost on the way to the monitor (the simulator never skips TRUTH).
  int64_t truth_gaps() const { return truth_gaps_; }

 private:
  void OnForce(const ForceEstimate& estimate);
  void OnTruth(const TruthSample& sample);
  void OnStatus(const estimator_status_t& status);

  ChannelNames channels_;
  ChannelRoutes<MonitorChannel> routes_;
  std::vector<ForceEstimate> forces_;
  std::vector<TruthSample> truth_;
  std::vector<int64_t> fault_utimes_;
  ForceStreamStats force_stats_;
  FlagRises rises_[32];  // by bit position
  estimator_status_t latest_status_;
  double strain_nis_sum_ = 0;
  int64_t strain_nis_reports_ = 0;
  double strain_nis_max_ = std::numeric_limits<double>::quiet_NaN();
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
