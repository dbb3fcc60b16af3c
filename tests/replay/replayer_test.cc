// The simulator -> log -> replay pipeline (hover, thrust_loss) with accuracy
// bounds at 1.5x the measured figures, byte-identical repeated replays, and the daemon fed the
// log over LCM (memq://) giving exactly the replay's estimates.
#include "replay/replayer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "evaluation/eval_metrics.h"
#include "evaluation/eval_runner.h"
#include "sources/lcm_source.h"
#include "tests/replay/replay_test_support.h"

namespace birotor {
namespace {

// Simulates the first duration_s of a scenario into an input log and
// estimates on the way (in-process run).
EvalRun SimulateToLog(const std::string& scenario, double duration_s, const std::string& log_path) {
  LogWriter writer;
  std::string error;
  EXPECT_TRUE(writer.Open(log_path, &error)) << error;
  EstimatorConfig config;
  EvalRun run = RunSimulatedScenario(ReferenceScenario(scenario), config, duration_s, &writer);
  EXPECT_TRUE(writer.Close());
  return run;
}

void ReplayToFile(const std::string& input, const std::string& output, const EstimatorConfig& config) {
  LogWriter writer;
  std::string error;
  ASSERT_TRUE(writer.Open(output, &error)) << error;
  LogSink sink(&writer);
  Replayer replayer(config, ReplayOptions{}, &sink);
  std::string damage = "unset";
  ASSERT_TRUE(ReplayLogFile(input, &replayer, &damage, &error)) << error;
  EXPECT_EQ(damage, "");
  ASSERT_TRUE(writer.Close());
  EXPECT_FALSE(sink.failed());
  EXPECT_GT(replayer.stats().forces, 0);
  EXPECT_GT(replayer.service().status_published(), 0);
}

TEST(ReplayPipelineTest, HoverSimToLogToReplayIsAccurateAndDeterministic) {
  const std::string input = TempPath("hover_in.lcm");
  const EvalRun live = SimulateToLog("hover", 3.0, input);
  const EvalResult result = Evaluate(live.forces, live.truth, {}, EvalOptions{});
  EXPECT_GT(result.paired, 2900);
  EXPECT_EQ(result.unpaired, 0);
  EXPECT_EQ(result.nonfinite, 0);
  EXPECT_EQ(result.fault_flags, 0);
  for (int r = 0; r < 2; ++r) {
    EXPECT_LT(result.rotor[r].mae_n, 1.5 * 0.0737) << "rotor " << r + 1;  // measured 0.0732 / 0.0737 N
  }

  // Same log twice: identical bytes.
  EstimatorConfig config;
  const std::string out_a = TempPath("hover_out_a.lcm");
  const std::string out_b = TempPath("hover_out_b.lcm");
  ReplayToFile(input, out_a, config);
  ReplayToFile(input, out_b, config);
  const std::string bytes_a = ReadFileBytes(out_a);
  ASSERT_GT(bytes_a.size(), 0u);
  EXPECT_TRUE(bytes_a == ReadFileBytes(out_b));

  // The log replay gives the numbers of the in-process run.
  ForceTruthCollector collector(MakeChannelNames());
  LogReader reader;
  std::string error;
  ASSERT_TRUE(reader.Open(out_a, &error));
  LogEvent event;
  while (reader.Next(&event)) {
    collector.Publish(event.channel, event.timestamp_us, event.data.data(), event.data.size());
  }
  ASSERT_EQ(collector.forces.size(), live.forces.size());
  ASSERT_EQ(collector.truth.size(), live.truth.size());
  for (size_t k = 0; k < live.forces.size(); ++k) {
    ASSERT_EQ(collector.forces[k].utime, live.forces[k].utime);
    ASSERT_EQ(collector.forces[k].force_n[0], live.forces[k].force_n[0]);
    ASSERT_EQ(collector.forces[k].force_n[1], live.forces[k].force_n[1]);
  }
}

TEST(ReplayPipelineTest, ThrustLossIsTrackedAndFlaggedThroughTheLog) {
  const std::string input = TempPath("thrust_loss_in.lcm");
  SimulateToLog("thrust_loss", 6.0, input);  // rotor 2: s 1 -> 0.75 at 5 s
  const std::string output = TempPath("thrust_loss_out.lcm");
  ReplayToFile(input, output, EstimatorConfig{});
  EvalRun run;
  std::string error;
  ASSERT_TRUE(RunLog(input, EstimatorConfig{}, &run, &error)) << error;
  const EvalResult result = Evaluate(run.forces, run.truth, {}, EvalOptions{});
  ASSERT_EQ(result.step_rotor, 2);
  EXPECT_NEAR(result.step_time_s, 5.0, 1e-3);
  ASSERT_FALSE(std::isnan(result.detection_delay_s)) << "fault never flagged";
  // Measured: delay 27.0 ms, scale error 0.0114, MAE 0.0742 / 0.0946 N; bounds 1.5x.
  EXPECT_LT(result.detection_delay_s, 1.5 * 0.027);
  EXPECT_LT(result.scale_error_after_step, 1.5 * 0.0114);
  EXPECT_EQ(result.false_alarms, 0);
  EXPECT_EQ(result.nonfinite, 0);
  for (int r = 0; r < 2; ++r) EXPECT_LT(result.rotor[r].mae_n, 1.5 * 0.0946);
}

// The daemon's glue fed the log's events over LCM, as lcm-logplayer would,
// publishes the same FORCE bytes as birotor-replay.
TEST(ReplayPipelineTest, DaemonFedTheLogOverLcmMatchesTheReplay) {
  const std::string input = TempPath("daemon_in.lcm");
  SimulateToLog("hover", 1.0, input);
  const std::string output = TempPath("daemon_replay_out.lcm");
  ReplayToFile(input, output, EstimatorConfig{});
  const ChannelNames channels = MakeChannelNames();
  const std::vector<std::vector<uint8_t>> replay_forces = ChannelPayloads(output, channels.force);

  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  LcmSink sink(&lcm);
  EstimatorConfig config;
  EstimatorService service(config, channels, EstimatorServiceOptions{}, &sink);
  LcmSource source(&lcm);
  std::string error;
  ASSERT_TRUE(source.Subscribe(service.InputChannels(), &service, &error)) << error;
  struct Capture {
    std::vector<std::vector<uint8_t>> forces;
    static void On(const lcm::ReceiveBuffer* b, const std::string&, Capture* self) {
      const uint8_t* data = static_cast<const uint8_t*>(b->data);
      self->forces.emplace_back(data, data + b->data_size);
    }
  } capture;
  lcm.subscribeFunction(channels.force, &Capture::On, &capture);
  LogReader reader;
  ASSERT_TRUE(reader.Open(input, &error)) << error;
  LogEvent event;
  while (reader.Next(&event)) {
    lcm.publish(event.channel, event.data.data(), static_cast<unsigned>(event.data.size()));
    while (lcm.handleTimeout(0) > 0) {
    }
  }
  ASSERT_EQ(capture.forces.size(), replay_forces.size());
  EXPECT_TRUE(capture.forces == replay_forces);
}

}  // namespace
}  // namespace birotor
