// Simulated or logged inputs through the replay core, outputs collected.
#include "evaluation/eval_runner.h"

#include <chrono>

#include "simulator/simulator.h"
#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

// Encodes every simulated sample as the wire message and hands it to the
// replayer (and optionally to an input log), as birotor-sim --output would.
class EncodingSink : public SampleSink {
 public:
  EncodingSink(const ChannelNames& channels, Replayer* replayer, LogWriter* log)
      : channels_(channels), replayer_(replayer), log_(log) {}
  void OnStrain(const StrainSample& s) override { Emit(channels_.strain, s.utime, ToMessage(s)); }
  void OnMotor(const MotorSample& s) override { Emit(channels_.motor, s.utime, ToMessage(s)); }
  void OnImu(const ImuSample& s) override { Emit(channels_.imu, s.utime, ToMessage(s)); }
  void OnPose(const PoseSample& s) override { Emit(channels_.pose, s.utime, ToMessage(s)); }
  void OnTruth(const TruthSample& s) override { Emit(channels_.truth, s.utime, ToMessage(s)); }

 private:
  template <class Msg>
  void Emit(const std::string& channel, int64_t utime, const Msg& message) {
    EncodeMessage(message, &buffer_);
    if (log_ != nullptr) log_->Write(channel, utime, buffer_.data(), buffer_.size());
    replayer_->Process(channel, utime, buffer_.data(), buffer_.size());
  }
  const ChannelNames& channels_;
  Replayer* replayer_;
  LogWriter* log_;
  std::vector<uint8_t> buffer_;
};

}  // namespace

ForceTruthCollector::ForceTruthCollector(const ChannelNames& channels, MessageSink* next)
    : channels_(channels), next_(next) {}

void ForceTruthCollector::Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) {
  if (channel == channels_.force) {
    if (DecodeMessage(data, size, &force_message_) == DecodeError::kNone) {
      forces.push_back(FromMessage(force_message_));
    } else {
      ++decode_errors;
    }
  } else if (channel == channels_.truth) {
    if (DecodeMessage(data, size, &truth_message_) == DecodeError::kNone) {
      truth.push_back(FromMessage(truth_message_));
    } else {
      ++decode_errors;
    }
  }
  if (next_ != nullptr) next_->Publish(channel, timestamp_us, data, size);
}

EvalRun RunSimulatedScenario(const Scenario& scenario, const EstimatorConfig& config, double max_duration_s,
                             LogWriter* input_log) {
  const auto start = std::chrono::steady_clock::now();
  ReplayOptions options;
  const ChannelNames channels = MakeChannelNames(options.prefix);
  ForceTruthCollector collector(channels);
  Replayer replayer(config, options, &collector);
  EncodingSink sink(channels, &replayer, input_log);
  Simulator simulator(scenario);
  while (!simulator.done() && (max_duration_s <= 0 || simulator.time_s() < max_duration_s)) {
    simulator.Step(&sink);
  }
  EvalRun run;
  run.simulated_s = simulator.time_s();
  run.forces = std::move(collector.forces);
  run.truth = std::move(collector.truth);
  run.stats = replayer.stats();
  run.health = replayer.service().health();
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

bool RunLog(const std::string& path, const EstimatorConfig& config, EvalRun* run, std::string* error,
            double min_usable_fraction) {
  const auto start = std::chrono::steady_clock::now();
  ReplayOptions options;
  const ChannelNames channels = MakeChannelNames(options.prefix);
  ForceTruthCollector collector(channels);
  Replayer replayer(config, options, &collector);
  if (!ReplayLogFile(path, &replayer, &run->log_damage, error, min_usable_fraction)) return false;
  run->forces = std::move(collector.forces);
  run->truth = std::move(collector.truth);
  run->stats = replayer.stats();
  run->health = replayer.service().health();
  run->simulated_s = run->stats.last_utime > run->stats.first_utime
                         ? static_cast<double>(run->stats.last_utime - run->stats.first_utime) * 1e-6
                         : 0.0;
  run->wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

}  // namespace birotor
