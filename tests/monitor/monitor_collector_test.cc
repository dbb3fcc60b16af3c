// MonitorCollector: pairing and fault inference on hand-made packets, and a
// simulator -> estimator daemon -> monitor run over memq:// whose figures are
// exactly those birotor-eval computes in-process for the same scenario.
#include "monitor/monitor_collector.h"

#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "evaluation/eval_runner.h"
#include "params/estimator_config_yaml.h"
#include "services/estimator_service.h"
#include "simulator/scenario_yaml.h"
#include "simulator/simulator.h"
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
  collector->HandlePacket(channel, bytes.data(), bytes.size());
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
  collector.HandlePacket(channels.force, garbage, sizeof(garbage));
  collector.HandlePacket("OTHER_CHANNEL", garbage, sizeof(garbage));

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
  EXPECT_FALSE(collector.health().received);
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
  const MonitorHealth& health = collector.health();
  ASSERT_TRUE(health.received);
  EXPECT_EQ(health.method, "ekf");
  EXPECT_EQ(health.strain_received, 100);
  EXPECT_EQ(health.strain_fused, 97);
  EXPECT_EQ(health.strain_faults, 3);
  EXPECT_EQ(health.dropped_overload, 3);
  EXPECT_EQ(health.resets, 4);
  EXPECT_EQ(collector.status_messages(), 1);
}

// Publishes every simulated sample on LCM, as birotor-sim does live.
class LcmPublishingSink : public SampleSink {
 public:
  LcmPublishingSink(lcm::LCM* lcm, const ChannelNames& channels) : lcm_(lcm), channels_(channels) {}
  void OnStrain(const StrainSample& s) override { Publish(channels_.strain, ToMessage(s)); }
  void OnMotor(const MotorSample& s) override { Publish(channels_.motor, ToMessage(s)); }
  void OnImu(const ImuSample& s) override { Publish(channels_.imu, ToMessage(s)); }
  void OnPose(const PoseSample& s) override { Publish(channels_.pose, ToMessage(s)); }
  void OnTruth(const TruthSample& s) override { Publish(channels_.truth, ToMessage(s)); }

 private:
  template <class Msg>
  void Publish(const std::string& channel, const Msg& message) {
    lcm_->publish(channel, &message);
  }
  lcm::LCM* lcm_;
  const ChannelNames& channels_;
};

void Drain(lcm::LCM* lcm) {
  while (lcm->handleTimeout(0) > 0) {
  }
}

// The demo's claim: simulator, daemon and monitor connected by LCM give the
// numbers birotor-eval computes for the same scenario and seed. memq:// keeps
// the order and loses nothing, as loopback UDP does when no buffer overflows.
TEST(MonitorCollectorTest, FiguresOverLcmEqualBirotorEval) {
  const Scenario scenario =
      LoadScenario(std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/gentle.yaml", {"scenario.duration_s=1.5"});
  const EstimatorConfig config = LoadEstimatorConfig(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");

  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  const ChannelNames channels = MakeChannelNames();
  LcmSink daemon_output(&lcm);
  EstimatorService daemon(config, channels, EstimatorServiceOptions{}, &daemon_output);
  daemon.Subscribe(&lcm);
  MonitorCollector collector(channels, scenario.duration_s);
  for (const std::string* channel : {&channels.truth, &channels.force}) {
    lcm.subscribeFunction(
        *channel,
        +[](const lcm::ReceiveBuffer* buffer, const std::string& name, MonitorCollector* c) {
          c->HandlePacket(name, buffer->data, buffer->data_size);
        },
        &collector);
  }
  LcmPublishingSink sink(&lcm, channels);
  Simulator simulator(scenario);
  while (simulator.Step(&sink)) Drain(&lcm);
  Drain(&lcm);
  daemon.Unsubscribe();

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

}  // namespace
}  // namespace birotor
