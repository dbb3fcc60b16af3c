// Simulated or logged inputs through the replay core, outputs collected.
#include "evaluation/eval_runner.h"

#include "simulator/simulator.h"
#include "sinks/wire_sample_sink.h"
#include "transport/host_clock.h"
#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {
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
  const Stopwatch stopwatch;
  ReplayOptions options;
  const ChannelNames channels = MakeChannelNames(options.prefix);
  ForceTruthCollector collector(channels);
  Replayer replayer(config, options, &collector);
  // Every simulated sample as birotor-sim --output writes it: into the input
  // log (when given), then through the replay.
  LogSink log_sink(input_log);
  TeeSink inputs(input_log != nullptr ? &log_sink : nullptr, &replayer);
  WireSampleSink sink(channels, &inputs);
  Simulator simulator(scenario);
  while (!simulator.done() && (max_duration_s <= 0 || simulator.time_s() < max_duration_s)) {
    simulator.Step(&sink);
  }
  EvalRun run;
  run.simulated_s = simulator.time_s();
  run.liftoff_utime = simulator.liftoff_utime();
  run.forces = std::move(collector.forces);
  run.truth = std::move(collector.truth);
  run.stats = replayer.stats();
  run.health = replayer.service().health();
  run.wall_s = stopwatch.ElapsedS();
  return run;
}

bool RunLog(const std::string& path, const EstimatorConfig& config, EvalRun* run, std::string* error,
            double min_usable_fraction) {
  const Stopwatch stopwatch;
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
  run->wall_s = stopwatch.ElapsedS();
  return true;
}

}  // namespace birotor
