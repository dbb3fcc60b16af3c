// The flight as recorded on the vehicle, for the tests that deploy what the
// estimator learned: the lock-step simulator's packets through the estimator
// daemon's own service, both into one LCM log.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "birotor/estimator_learned_n_t.hpp"
#include "birotor/estimator_status_t.hpp"
#include "estimator/estimator_config.h"
#include "estimator/gauge_calibration.h"
#include "replay/replayer.h"
#include "simulator/simulator.h"
#include "sinks/message_sink.h"
#include "sinks/wire_sample_sink.h"
#include "transport/channels.h"
#include "transport/log_io.h"

namespace birotor {
namespace testing_support {

// Flies scenario into the log at path through the service (config),
// started from `persisted` (optional: the gauge state file the daemon
// restored); `forged` and `forged_learned` (optional) are appended 1 ms
// after the newest input. Returns the estimator's final state (what it
// persists at a clean stop).
inline PipelineHealth RecordFlightLog(const Scenario& scenario, const EstimatorConfig& config, const std::string& path,
                                      const estimator_status_t* forged = nullptr,
                                      const GaugeCalibration* persisted = nullptr,
                                      const estimator_learned_n_t* forged_learned = nullptr) {
  LogWriter writer;
  std::string error;
  EXPECT_TRUE(writer.Open(path, &error)) << error;
  LogSink log(&writer);
  ReplayOptions options;
  options.copy_truth = false;  // TRUTH reaches the log from the simulator
  Replayer estimator(config, options, &log);
  if (persisted != nullptr) estimator.service().SetGaugeOffsets(*persisted);
  TeeSink both(&log, &estimator);
  WireSampleSink wire(MakeChannelNames(), &both);
  Simulator simulator(scenario);
  simulator.Run(&wire);
  if (forged != nullptr) {
    EXPECT_TRUE(writer.WriteMessage(MakeChannelNames().estimator_status, estimator.stats().last_utime + 1000, *forged));
  }
  if (forged_learned != nullptr) {
    EXPECT_TRUE(writer.WriteMessage(MakeChannelNames().estimator_learned_n, estimator.stats().last_utime + 1000,
                                    *forged_learned));
  }
  EXPECT_TRUE(writer.Close()) << writer.error();
  return estimator.service().health();
}

}  // namespace testing_support
}  // namespace birotor
