// MonitorCollector: pairing and fault inference on hand-made packets, and a
// simulator -> estimator daemon -> monitor run over memq:// whose figures are
// exactly those birotor-eval computes in-process for the same scenario.
#include "monitor/monitor_collector.h"

#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "evaluation/eval_runner.h"
#include "monitor/monitor_view.h"
#include "nodes/estimator_service.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "simulator/simulator.h"
#include "sinks/message_sink.h"
#include "sinks/wire_sample_sink.h"
#include "sources/lcm_source.h"
#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

template <class Msg>
std::vector<uint8_t> Encode(const Msg& message) {
  std::vector<uint8_t> buffer;
  EncodeMessage(message, &buffer);
  return buffer;
}

template <class Msg>
void Feed(MonitorCollector* collector, const std::string& channel, const Msg& message) {
  const std::vector<uint8_t> bytes = Encode(message);
  collector->HandlePacket(channel, bytes.data(), bytes.size(), -1);
}

TruthSample Truth(int64_t utime, double f1_n, double f2_n) {
  TruthSample t;
  t.utime = utime;
  t.force_n[0] = f1_n;
  t.force_n[1] = f2_n;
  return t;
}

ForceEstimate Estimate(int64_t utime, int32_t seq, double f1_n, double f2_n, int32_t status = kStatusValid) {
  ForceEstimate e;
  e.utime = utime;
  e.seq = seq;
  e.force_n[0] = f1_n;
  e.force_n[1] = f2_n;
  e.force_std_n[0] = e.force_std_n[1] = 0.01;
  e.status = status;
  return e;
}

TEST(MonitorCollectorTest, PairsByUtimeAndScoresLikeEvaluate) {
  const ChannelNames channels = MakeChannelNames();
  MonitorCollector collector(channels, 1.0);
  // TRUTH every 1 ms with f = (3, 4) N; estimates off by (+0.1, -0.2) N. One
  // estimate has a utime with no truth (unpaired); FORCE may arrive before TRUTH.
  for (int k = 0; k < 1000; ++k) {
    const int64_t utime = 1000 * k;
    Feed(&collector, channels.force, ToMessage(Estimate(utime, k, 3.1, 3.8)));
    Feed(&collector, channels.truth, ToMessage(Truth(utime, 3.0, 4.0)));
  }
  Feed(&collector, channels.force, ToMessage(Estimate(999500, 1000, 3.0, 4.0)));
  const uint8_t garbage[3] = {1, 2, 3};
  collector.HandlePacket(channels.force, garbage, sizeof(garbage), -1);
  collector.HandlePacket("OTHER_CHANNEL", garbage, sizeof(garbage), -1);

  EvalOptions options;
  options.warmup_s = 0.1;
  const EvalResult result = collector.Evaluate(options);
  EXPECT_EQ(result.paired, 1000);
  EXPECT_EQ(result.unpaired, 1);
  EXPECT_EQ(result.rotor[0].count, 900);  // 0.1 s of 1 s unscored
  EXPECT_NEAR(result.rotor[0].mae_n, 0.1, 1e-9);
  EXPECT_NEAR(result.rotor[1].mae_n, 0.2, 1e-9);
  EXPECT_NEAR(result.rotor[1].max_n, 0.2, 1e-9);
  EXPECT_EQ(collector.decode_errors(), 1);
  EXPECT_EQ(collector.truth_gaps(), 0);
  EXPECT_TRUE(collector.fault_utimes().empty());

  const EvalResult direct = Evaluate(collector.forces(), collector.truth(), {}, options);
  EXPECT_EQ(MarkdownTableRow("s", "m", result), MarkdownTableRow("s", "m", direct));
}

TEST(MonitorCollectorTest, InfersFaultsFromSeqJumpsAndResets) {
  const ChannelNames channels = MakeChannelNames("V2_");
  MonitorCollector collector(channels, 1.0);
  Feed(&collector, channels.force, ToMessage(Estimate(0, 2147483646, 1, 1)));
  Feed(&collector, channels.force, ToMessage(Estimate(1000, 2147483647, 1, 1)));
  Feed(&collector, channels.force, ToMessage(Estimate(2000, -2147483647 - 1, 1, 1)));  // wrap: no fault
  Feed(&collector, channels.force, ToMessage(Estimate(4000, -2147483647 + 1, 1, 1)));  // one missing
  Feed(&collector, channels.force, ToMessage(Estimate(5000, -2147483647 + 2, 1, 1, kStatusFilterReset)));
  EXPECT_EQ(collector.fault_utimes(), (std::vector<int64_t>{4000, 5000}));
  EXPECT_EQ(collector.force_stats().seq_gaps, 1);
  EXPECT_EQ(collector.force_stats().seq_missing, 1);
  EXPECT_EQ(collector.force_stats().resets_after_start, 1);
  EXPECT_EQ(collector.rises(kStatusFilterReset).count, 1);
  EXPECT_EQ(collector.rises(kStatusFilterReset).first_utime, 5000);

  // TRUTH at 1 kHz with one lost packet; other prefixes are ignored.
  for (int64_t utime : {0, 1000, 2000, 4000, 5000}) {
    Feed(&collector, channels.truth, ToMessage(Truth(utime, 1, 1)));
  }
  Feed(&collector, "BIROTOR_TRUTH", ToMessage(Truth(6000, 1, 1)));
  EXPECT_EQ(collector.truth().size(), 5u);
  EXPECT_EQ(collector.truth_gaps(), 1);
}

TEST(MonitorCollectorTest, KeepsNewestEstimatorHealth) {
  const ChannelNames channels = MakeChannelNames();
  MonitorCollector collector(channels, 1.0);
  EXPECT_FALSE(collector.has_status());
  estimator_status_t status{};
  status.method = "ekf";
  status.num_inputs = 2;
  status.inputs.resize(2);
  status.inputs[0].channel = "STRAIN";
  status.inputs[0].received = 100;
  status.inputs[0].fused = 97;
  status.inputs[0].gaps = 1;
  status.inputs[0].rejected_invalid = 2;
  status.inputs[0].dropped_overload = 3;
  status.inputs[1].channel = "MOTOR";
  status.inputs[1].received = 50;
  status.resets = 4;
  status.last_reset_reason = "gap";
  Feed(&collector, channels.estimator_status, status);
  ASSERT_TRUE(collector.has_status());
  EXPECT_EQ(collector.latest_status().method, "ekf");
  EXPECT_EQ(collector.latest_status().resets, 4);
  ASSERT_NE(collector.input("STRAIN"), nullptr);
  EXPECT_EQ(collector.input("STRAIN")->received, 100);
  EXPECT_EQ(collector.input("STRAIN")->fused, 97);
  EXPECT_EQ(collector.input("STRAIN")->dropped_overload, 3);
  EXPECT_EQ(collector.input("MOTOR")->received, 50);
  EXPECT_EQ(collector.input("IMU"), nullptr);
  EXPECT_EQ(collector.status_messages(), 1);
}

// issue 14: a perfect run starts with the estimator's FILTER_RESET (reason
// "start"); that is neither a loss nor a fault.
TEST(MonitorCollectorTest, StartUpResetIsNeitherALossNorAnAlarm) {
  const ChannelNames channels = MakeChannelNames();
  MonitorCollector collector(channels, 1.0);
  Feed(&collector, channels.force, ToMessage(Estimate(0, 0, 1, 1, kStatusFilterReset | kStatusConverging)));
  for (int k = 1; k < 100; ++k) Feed(&collector, channels.force, ToMessage(Estimate(1000 * k, k, 1, 1)));
  EXPECT_EQ(collector.force_stats().resets_after_start, 0);
  EXPECT_EQ(collector.force_stats().seq_gaps, 0);
  EXPECT_EQ(collector.rises(kStatusFilterReset).count, 0);
  EXPECT_EQ(collector.rises(kStatusValid).count, 1);  // VALID rose at 1 ms
  EXPECT_EQ(collector.rises(kStatusValid).first_utime, 1000);
  EXPECT_EQ(collector.force_stats().valid, 99);
}

void Drain(lcm::LCM* lcm) {
  while (lcm->handleTimeout(0) > 0) {
  }
}

// Simulator -> estimator daemon -> collector over memq:// (in order, nothing
// lost), with ESTIMATOR_STATUS on the vehicle clock; TRUTH only if publish_truth.
void FlyOverMemq(const Scenario& scenario, const EstimatorConfig& config, bool publish_truth,
                 MonitorCollector* collector) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  const ChannelNames channels = MakeChannelNames();
  LcmSink daemon_output(&lcm);
  EstimatorService daemon(config, channels, EstimatorServiceOptions{}, &daemon_output);
  LcmSource source(&lcm);
  std::string error;
  ASSERT_TRUE(source.Subscribe(daemon.InputChannels(), &daemon, &error)) << error;
  for (const std::string* channel : {&channels.truth, &channels.force, &channels.estimator_status}) {
    lcm.subscribeFunction(
        *channel,
        +[](const lcm::ReceiveBuffer* buffer, const std::string& name, MonitorCollector* c) {
          c->HandlePacket(name, buffer->data, buffer->data_size, -1);
        },
        collector);
  }
  LcmSink simulator_output(&lcm);
  WireSampleSink sink(channels, &simulator_output, publish_truth);  // as birotor-sim does live
  Simulator simulator(scenario);
  while (simulator.Step(&sink)) {
    Drain(&lcm);
    daemon.PublishStatusOnVehicleClock();
  }
  Drain(&lcm);
}

// The demo's claim: simulator, daemon and monitor connected by LCM give the
// numbers birotor-eval computes for the same scenario and seed. memq:// keeps
// the order and loses nothing, as loopback UDP does when no buffer overflows.
TEST(MonitorCollectorTest, FiguresOverLcmEqualBirotorEval) {
  const Scenario scenario =
      LoadScenario(std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/gentle.yaml", {"scenario.duration_s=1.5"});
  const EstimatorConfig config = LoadEstimatorConfig(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");

  MonitorCollector collector(MakeChannelNames(), scenario.duration_s);
  FlyOverMemq(scenario, config, /*publish_truth=*/true, &collector);

  const EvalRun eval = RunSimulatedScenario(scenario, config);
  ASSERT_EQ(collector.forces().size(), eval.forces.size());
  ASSERT_EQ(collector.truth().size(), eval.truth.size());
  for (size_t i = 0; i < eval.forces.size(); ++i) {
    ASSERT_EQ(collector.forces()[i].utime, eval.forces[i].utime) << i;
    ASSERT_EQ(collector.forces()[i].force_n[0], eval.forces[i].force_n[0]) << i;
    ASSERT_EQ(collector.forces()[i].force_n[1], eval.forces[i].force_n[1]) << i;
  }
  const EvalOptions options;
  const EvalResult monitor = collector.Evaluate(options);
  const EvalResult reference = Evaluate(eval.forces, eval.truth, eval.stats.strain_fault_utimes, options);
  EXPECT_GT(monitor.paired, 1400);
  EXPECT_EQ(MarkdownTableRow("gentle", config.method, monitor), MarkdownTableRow("gentle", config.method, reference));
}

// issue 14 item 3: a real vehicle has no TRUTH. Simulator (TRUTH switched
// off) -> estimator daemon -> monitor over memq://: the monitor holds every
// FORCE the in-process run makes, the estimator's health, and calls a clean
// run clean.
TEST(MonitorCollectorTest, VehicleViewOverLcmWithoutTruth) {
  const Scenario scenario =
      LoadScenario(std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/gentle.yaml", {"scenario.duration_s=1.5"});
  const EstimatorConfig config = LoadEstimatorConfig(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");

  MonitorCollector collector(MakeChannelNames(), scenario.duration_s);
  FlyOverMemq(scenario, config, /*publish_truth=*/false, &collector);

  const EvalRun eval = RunSimulatedScenario(scenario, config);
  EXPECT_FALSE(collector.has_truth());
  ASSERT_EQ(collector.forces().size(), eval.forces.size());
  int64_t valid = 0;
  for (size_t i = 0; i < eval.forces.size(); ++i) {
    ASSERT_EQ(collector.forces()[i].force_n[1], eval.forces[i].force_n[1]) << i;
    ASSERT_EQ(collector.forces()[i].force_std_n[1], eval.forces[i].force_std_n[1]) << i;
    valid += (eval.forces[i].status & kStatusValid) != 0;
  }
  EXPECT_EQ(collector.force_stats().valid, valid);
  // 1.5 s at the vehicle-clock status rate of 5 Hz (EstimatorServiceOptions).
  EXPECT_GE(collector.status_messages(), 7);
  ASSERT_NE(collector.input("STRAIN"), nullptr);
  // The newest status is at most one 5 Hz period (200 strain samples at 1 kHz) old.
  EXPECT_LE(collector.input("STRAIN")->received, static_cast<int64_t>(eval.forces.size()));
  EXPECT_GE(collector.input("STRAIN")->received, static_cast<int64_t>(eval.forces.size()) - 200);
  EXPECT_EQ(collector.force_stats().seq_gaps, 0);
  EXPECT_EQ(collector.force_stats().resets_after_start, 0);
  EXPECT_EQ(DeliveryNote(collector), "");  // a perfect run has nothing to excuse
  const std::string summary = VehicleSummaryText(collector);
  EXPECT_NE(summary.find("FORCE " + std::to_string(eval.forces.size()) + " messages"), std::string::npos) << summary;
  EXPECT_NE(summary.find("estimator ekf: resets 1 (last: start)"), std::string::npos) << summary;
}

}  // namespace
}  // namespace birotor
