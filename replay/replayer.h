// The core of birotor-replay, shared with birotor-eval and the tests: feeds
// recorded (or freshly simulated) input packets through the daemon's own
// EstimatorService as fast as possible, with ESTIMATOR_STATUS on the vehicle
// clock, so the output is deterministic. Its output goes to a MessageSink
// (sinks/: a log, the CSV trace, a test collector).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "estimator/estimator_config.h"
#include "nodes/estimator_service.h"
#include "nodes/multi_arm_estimator_service.h"
#include "sinks/message_sink.h"
#include "sources/message_source.h"
#include "transport/channels.h"

namespace birotor {

struct ReplayOptions {
  std::string prefix = kDefaultChannelPrefix;  // channel prefix of input and output
  bool copy_truth = true;                      // copy TRUTH events to the output (for evaluation)
  double status_rate_hz = 5.0;                 // ESTIMATOR_STATUS rate on the vehicle clock [Hz]
};

// What a replay saw.
struct ReplayStats {
  int64_t events = 0;         // events offered to the replayer
  int64_t input_packets = 0;  // STRAIN, MOTOR, IMU, POSE packets (STRAIN_N, MOTOR_N, IMU, POSE)
  int64_t truth_copied = 0;
  int64_t forces = 0;        // FORCE messages written
  int64_t first_utime = -1;  // newest-sample utime range of the inputs [us]
  int64_t last_utime = -1;
  // Vehicle times [us] at which the pipeline counted an input fault on the
  // strain channel (gap, out of order, duplicate, invalid, decode error) or
  // reset: for evaluating accuracy away from faults.
  std::vector<int64_t> strain_fault_utimes;
};

// Runs packets through one estimator node: EstimatorService (the birotor's
// channels; Replayer) or MultiArmEstimatorService (a vehicle description
// with N arms, the counted channels; MultiArmReplayer, birotor-replay
// --vehicle). Not thread-safe. It is a PacketHandler, so a MessageSource (a
// log file) feeds it, and a MessageSink, so a producer (the simulator
// through WireSampleSink) can publish straight into it.
template <class Service>
class BasicReplayer : public MessageSink, public PacketHandler {
 public:
  BasicReplayer(const EstimatorConfig& config, const ReplayOptions& options, MessageSink* sink);

  // One event of a log (or a simulated packet): inputs go to the estimator,
  // TRUTH and TRUTH_N are copied through when asked, anything else is ignored.
  void Process(std::string_view channel, int64_t timestamp_us, const void* data, size_t size);
  void Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) override {
    Process(channel, timestamp_us, data, size);
  }
  // From a source: receive_wall_utime (a log's recorded time) stamps the
  // copied TRUTH; the estimator gets no receive time, so its overload guard
  // stays off and the output is deterministic.
  void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t receive_wall_utime) override {
    Process(channel, receive_wall_utime, data, size);
  }

  const ReplayStats& stats() const { return stats_; }
  const Service& service() const { return service_; }
  Service& service() { return service_; }  // e.g. to restore a gauge state file before the first packet
  const ChannelNames& channels() const { return channels_; }

 private:
  int64_t StrainFaultCount() const;

  ReplayOptions options_;
  ChannelNames channels_;
  MessageSink* sink_;
  Service service_;
  ReplayStats stats_;
  int64_t strain_fault_count_ = 0;
};

using Replayer = BasicReplayer<EstimatorService>;
using MultiArmReplayer = BasicReplayer<MultiArmEstimatorService>;

// Replays every event of the log at input_path. False with a one-line *error
// when the log cannot be opened or is not usable (CheckLogUsable of
// transport/log_io.h: empty, no readable event, less than
// min_usable_fraction of its bytes readable). *damage (optional) gets a
// warning line when a usable log had corrupt events or a cut tail.
bool ReplayLogFile(const std::string& input_path, PacketHandler* replayer, std::string* damage, std::string* error,
                   double min_usable_fraction = kDefaultMinUsableLogFraction);

}  // namespace birotor
