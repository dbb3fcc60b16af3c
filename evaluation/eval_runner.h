// One evaluation run of birotor-eval: a scenario simulated in-process (or an
// input log) fed as encoded packets through the replay core, with the FORCE
// and TRUTH messages collected for scoring and plotting.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "birotor/force_estimate_t.hpp"
#include "birotor/truth_t.hpp"
#include "estimator/estimator_config.h"
#include "replay/replayer.h"
#include "samples/samples.h"
#include "simulator/scenario.h"

namespace birotor {

// Collects FORCE and TRUTH (decoded) and forwards every message to next.
class ForceTruthCollector : public MessageSink {
 public:
  ForceTruthCollector(const ChannelNames& channels, MessageSink* next = nullptr);
  void Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) override;

  std::vector<ForceEstimate> forces;
  std::vector<TruthSample> truth;
  int64_t decode_errors = 0;

 private:
  ChannelNames channels_;
  MessageSink* next_;
  force_estimate_t force_message_;
  truth_t truth_message_;
};

struct EvalRun {
  std::vector<ForceEstimate> forces;
  std::vector<TruthSample> truth;
  ReplayStats stats;
  PipelineHealth health;
  double simulated_s = 0;      // [s]
  double wall_s = 0;           // simulation and estimation [s]
  int64_t liftoff_utime = -1;  // first lift-off of a scenario with a ground phase [us]; -1 if none
  std::string log_damage;      // input log only: corrupt events or a cut tail ("" if intact)
};

// Simulates the scenario (up to max_duration_s, <= 0 for all of it) and
// estimates with config. When log is given, the simulated inputs and TRUTH
// are also written to it (a sim-to-log pipeline in one pass).
EvalRun RunSimulatedScenario(const Scenario& scenario, const EstimatorConfig& config, double max_duration_s = 0,
                             LogWriter* input_log = nullptr);

// Estimates over an input log. False with *error if it cannot be read or is
// not usable (see ReplayLogFile); run->log_damage warns of a damaged log.
bool RunLog(const std::string& path, const EstimatorConfig& config, EvalRun* run, std::string* error,
            double min_usable_fraction = kDefaultMinUsableLogFraction);

}  // namespace birotor
