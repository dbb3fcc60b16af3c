// ESTIMATOR_LEARNED_N (nodes/estimator_learned_message.h) through the
// estimator node as birotor-replay runs it, into a log file and decoded back:
// one per ESTIMATOR_STATUS with its utime and seq, the vehicle description's
// checksum and count, and per arm what the pipeline flies, learned or the
// file's. The birotor with tip-mass learning off and on and with the strain
// scales and body mass learned, the trirotor with its gauges' noise learned,
// and a log recorded before the type existed.
#include "nodes/estimator_learned_message.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "birotor/estimator_learned_n_t.hpp"
#include "birotor/estimator_status_t.hpp"
#include "model/vehicle_description_checksum.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "replay/replayer.h"
#include "simulator/multi_arm_simulator.h"
#include "simulator/simulator.h"
#include "sinks/message_sink.h"
#include "sinks/wire_sample_sink.h"
#include "transport/lcm_codec.h"
#include "transport/log_io.h"

namespace birotor {
namespace {

std::string SourceFile(const std::string& relative) { return std::string(BIROTOR_SOURCE_DIR) + "/" + relative; }
std::string TempLog(const std::string& name) { return ::testing::TempDir() + "/birotor_learned_" + name + ".lcm"; }

// What the pipeline held when one ESTIMATOR_LEARNED_N was published.
struct Snapshot {
  double tip_mass_kg = 0, tip_mass_std_kg = 0;
  double strain_noise_scale[kMaxSampleArms] = {};
};

// Writes the node's output to a log and notes the pipeline's health at each
// ESTIMATOR_LEARNED_N (published inside the status call, so it is the
// health the message was built from).
template <class Replayer>
class RecordingSink : public MessageSink {
 public:
  RecordingSink(const std::string& path, const ChannelNames& channels) : channels_(channels), log_sink_(&writer_) {
    std::string error;
    EXPECT_TRUE(writer_.Open(path, &error)) << error;
  }
  void Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) override {
    log_sink_.Publish(channel, timestamp_us, data, size);
    if (channel != channels_.estimator_learned_n || replayer == nullptr) return;
    snapshots.push_back(Take(replayer->service()));
  }
  void Close() {
    EXPECT_TRUE(writer_.Close());
    EXPECT_FALSE(log_sink_.failed());
  }
  const Replayer* replayer = nullptr;
  std::vector<Snapshot> snapshots;

 private:
  static Snapshot Take(const EstimatorService& service) {
    const PipelineHealth& health = service.pipeline().health();
    Snapshot s;
    s.tip_mass_kg = health.tip_mass_kg;
    s.tip_mass_std_kg = health.tip_mass_std_kg;
    for (int i = 0; i < 2; ++i) s.strain_noise_scale[i] = health.strain_noise_scale[i];
    return s;
  }
  static Snapshot Take(const MultiArmEstimatorService& service) {
    Snapshot s;
    for (int i = 0; i < kMaxSampleArms; ++i) {
      s.strain_noise_scale[i] = service.health().strain_noise_scale[static_cast<size_t>(i)];
    }
    return s;
  }
  ChannelNames channels_;
  LogWriter writer_;
  LogSink log_sink_;
};

// The statuses and learned values of an output log, in order; every
// ESTIMATOR_LEARNED_N must directly follow its ESTIMATOR_STATUS, stamped alike.
struct Output {
  std::vector<estimator_status_t> statuses;
  std::vector<estimator_learned_n_t> learned;
};

Output ReadOutput(const std::string& path, const ChannelNames& channels) {
  Output out;
  LogReader reader;
  std::string error;
  EXPECT_TRUE(reader.Open(path, &error)) << error;
  LogEvent event, previous;
  while (reader.Next(&event)) {
    if (event.channel == channels.estimator_status) {
      out.statuses.emplace_back();
      EXPECT_EQ(DecodeMessage(event.data.data(), event.data.size(), &out.statuses.back()), DecodeError::kNone);
    } else if (event.channel == channels.estimator_learned_n) {
      out.learned.emplace_back();
      EXPECT_EQ(DecodeMessage(event.data.data(), event.data.size(), &out.learned.back()), DecodeError::kNone);
      EXPECT_EQ(previous.channel, channels.estimator_status);
      EXPECT_EQ(previous.timestamp_us, event.timestamp_us);
    }
    previous = event;
  }
  EXPECT_EQ(out.learned.size(), out.statuses.size());
  for (size_t k = 0; k < out.learned.size() && k < out.statuses.size(); ++k) {
    EXPECT_EQ(out.learned[k].utime, out.statuses[k].utime) << k;
    EXPECT_EQ(out.learned[k].seq, out.statuses[k].seq) << k;
  }
  return out;
}

// The same double, NaN included.
bool Same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b)); }

EstimatorConfig BirotorConfig() { return LoadEstimatorConfig(SourceFile("config/estimator.yaml")); }

// The birotor's mismatch_tip_mass_plus20 flight (15 s, the tip masses 20 %
// above the file's) through the birotor's node; its output log decoded.
Output FlyBirotor(const EstimatorConfig& config, const std::string& name, std::vector<Snapshot>* snapshots) {
  const ChannelNames channels = MakeChannelNames();
  const std::string path = TempLog(name);
  RecordingSink<Replayer> sink(path, channels);
  Replayer replayer(config, ReplayOptions{}, &sink);
  sink.replayer = &replayer;
  WireSampleSink wire(channels, &replayer);
  Simulator simulator(LoadScenario(SourceFile("config/scenarios/mismatch_tip_mass_plus20.yaml")));
  simulator.Run(&wire);
  sink.Close();
  *snapshots = sink.snapshots;
  return ReadOutput(path, channels);
}

// config/reference_vehicle.yaml's birotor (docs/interface.md: 3c46c6d41f8659af).
void ExpectBirotorIdentity(const Output& out, const EstimatorConfig& config) {
  ASSERT_GE(out.learned.size(), 74u);  // 15 s at 5 Hz on the vehicle clock
  for (const estimator_learned_n_t& m : out.learned) {
    ASSERT_EQ(m.n_arms, 2);
    ASSERT_EQ(m.strain_scale.size(), 2u);
    EXPECT_EQ(m.vehicle_checksum, "3c46c6d41f8659af");
    EXPECT_EQ(m.vehicle_checksum, DescriptionChecksum(config.vehicle));
  }
}

// The gauges' noise sqrt(R_i) the EKF weighs them with: the file's 2e-5 rad
// times the square root of the learned variance scale (adapt_strain_noise,
// on by default), as the pipeline had it at publication.
void ExpectStrainNoiseAsFlown(const Output& out, const std::vector<Snapshot>& snapshots, double noise_rad, int arms) {
  ASSERT_EQ(snapshots.size(), out.learned.size());
  for (size_t k = 0; k < out.learned.size(); ++k) {
    EXPECT_EQ(out.learned[k].strain_noise_source, "learned");
    for (int i = 0; i < arms; ++i) {
      EXPECT_EQ(out.learned[k].strain_noise_rad[static_cast<size_t>(i)],
                std::sqrt(snapshots[k].strain_noise_scale[i]) * noise_rad)
          << k << " arm " << i + 1;
    }
  }
}

TEST(EstimatorLearnedMessageTest, BirotorWithoutLearningCarriesTheFileValues) {
  EstimatorConfig config = BirotorConfig();
  config.model_consistency.arm_mode_learn_tip_mass = false;  // on by default
  std::vector<Snapshot> snapshots;
  const Output out = FlyBirotor(config, "birotor_params", &snapshots);
  ExpectBirotorIdentity(out, config);
  ExpectStrainNoiseAsFlown(out, snapshots, config.ekf.strain_noise_rad, 2);
  for (const estimator_learned_n_t& m : out.learned) {
    for (size_t i = 0; i < 2; ++i) {
      EXPECT_EQ(m.strain_scale[i], 1.0);
      EXPECT_TRUE(std::isnan(m.strain_scale_std[i]));
      EXPECT_EQ(m.tip_mass_kg[i], 0.28812);  // config/reference_vehicle.yaml
      EXPECT_TRUE(std::isnan(m.tip_mass_std_kg[i]));
      // The simulated gauges have the file's noise: never below it (scale
      // at least 1), at most 2.215e-5 rad measured (arm 2), 1.5x that excess.
      EXPECT_GE(m.strain_noise_rad[i], 2e-5);
      EXPECT_LE(m.strain_noise_rad[i], 2e-5 * (1.0 + 1.5 * 0.1075));
    }
    EXPECT_EQ(m.strain_scale_source, "params");
    EXPECT_EQ(m.tip_mass_source, "params");
    EXPECT_EQ(m.body_mass_kg, 4.0);
    EXPECT_TRUE(std::isnan(m.body_mass_std_kg));
    EXPECT_EQ(m.body_mass_source, "params");
  }
}

// arm_mode_learn_tip_mass: the m_p the EKF flies, one for both arms, from
// the prior (0.15 x 0.28812 kg) to the flight's 0.345744 kg within 3 sigma
// + 5 g (the bound of tests/estimator/arm_mode_monitor_test.cc
// TipMassIsLearned, the same flight).
TEST(EstimatorLearnedMessageTest, BirotorTipMassLearnedWithItsSigma) {
  EstimatorConfig config = BirotorConfig();
  config.model_consistency.arm_mode_learn_tip_mass = true;
  std::vector<Snapshot> snapshots;
  const Output out = FlyBirotor(config, "birotor_tip_mass", &snapshots);
  ExpectBirotorIdentity(out, config);
  ExpectStrainNoiseAsFlown(out, snapshots, config.ekf.strain_noise_rad, 2);
  const estimator_learned_n_t& first = out.learned.front();
  EXPECT_EQ(first.tip_mass_source, "learned");
  EXPECT_DOUBLE_EQ(first.tip_mass_std_kg[0], 0.15 * 0.28812);
  for (size_t k = 0; k < out.learned.size(); ++k) {
    const estimator_learned_n_t& m = out.learned[k];
    EXPECT_EQ(m.tip_mass_source, "learned");
    for (size_t i = 0; i < 2; ++i) {
      EXPECT_EQ(m.tip_mass_kg[i], snapshots[k].tip_mass_kg) << k;
      EXPECT_EQ(m.tip_mass_std_kg[i], snapshots[k].tip_mass_std_kg) << k;
    }
    EXPECT_EQ(m.strain_scale_source, "params");  // the tip mass is learned only with the file's stiffness
    EXPECT_EQ(m.body_mass_source, "params");
  }
  const estimator_learned_n_t& last = out.learned.back();
  EXPECT_NEAR(last.tip_mass_kg[0], 0.345744, 3.0 * last.tip_mass_std_kg[0] + 0.005);
  EXPECT_LT(last.tip_mass_std_kg[0], 0.25 * first.tip_mass_std_kg[0]);  // measured 0.0032 kg of 0.0432
}

// learn_strain_scale and learn_body_mass: per arm what ESTIMATOR_STATUS
// says, bit for bit; the tip mass is learned beside the scales (the arm
// mode tells a stiffness from a tip mass: docs/mismatch.md "What a learned
// strain scale is").
TEST(EstimatorLearnedMessageTest, BirotorStrainScalesAndBodyMassAsOnTheStatus) {
  EstimatorConfig config = BirotorConfig();
  config.ekf.learn_strain_scale = true;
  config.ekf.learn_body_mass = true;
  std::vector<Snapshot> snapshots;
  const Output out = FlyBirotor(config, "birotor_scale_mass", &snapshots);
  ExpectBirotorIdentity(out, config);
  for (size_t k = 0; k < out.learned.size(); ++k) {
    const estimator_learned_n_t& m = out.learned[k];
    const estimator_status_t& s = out.statuses[k];
    for (size_t i = 0; i < 2; ++i) {
      EXPECT_TRUE(Same(m.strain_scale[i], s.strain_scale[i])) << k;
      EXPECT_TRUE(Same(m.strain_scale_std[i], s.strain_scale_std[i])) << k;
      EXPECT_TRUE(std::isfinite(m.tip_mass_kg[i]) && m.tip_mass_kg[i] > 0) << k;
    }
    EXPECT_EQ(m.strain_scale_source, s.strain_scale_source);
    EXPECT_EQ(m.body_mass_kg, s.body_mass_kg);
    EXPECT_TRUE(Same(m.body_mass_std_kg, s.body_mass_std_kg));
    EXPECT_EQ(m.body_mass_source, s.body_mass_source);
  }
  const estimator_learned_n_t& last = out.learned.back();
  EXPECT_EQ(last.tip_mass_source, "learned");
  EXPECT_TRUE(std::isfinite(last.tip_mass_std_kg[0]) && last.tip_mass_std_kg[0] > 0);
  EXPECT_EQ(last.strain_scale_source, "learned");
  EXPECT_EQ(last.body_mass_source, "learned");
  EXPECT_TRUE(std::isfinite(last.strain_scale_std[0]) && last.strain_scale_std[0] > 0);
  EXPECT_TRUE(std::isfinite(last.body_mass_std_kg) && last.body_mass_std_kg > 0);
}

// The trirotor's gentle flight with gauges twice as noisy as its file says
// (4e-5 rad): every arm's sqrt(R_i) learned towards 4e-5 (the learned
// variance scales measured 4.024 / 3.816 / 4.062 in
// tests/estimator/multi_arm_consistency_test.cc, asserted in [3, 5] there);
// the strain scales and body mass are the description's; the tip masses
// are learned from the arm mode (one r for every arm; the file's vehicle:
// within 3 sigma of the description's).
TEST(EstimatorLearnedMessageTest, TrirotorReportsEveryGaugesLearnedNoise) {
  EstimatorConfig config = LoadEstimatorConfig(SourceFile("config/estimator.yaml"));
  config.vehicle = LoadVehicleDescription(SourceFile("config/vehicles/trirotor.yaml"));
  const Scenario scenario = LoadScenario(SourceFile("config/scenarios/gentle.yaml"),
                                         {"scenario.duration_s=8", "sensors.strain.noise_rad=4.0e-5"}, 3);
  const ChannelNames channels = MakeChannelNames();
  const std::string path = TempLog("trirotor");
  RecordingSink<MultiArmReplayer> sink(path, channels);
  MultiArmReplayer replayer(config, ReplayOptions{}, &sink);
  sink.replayer = &replayer;
  WireSampleSink wire(channels, &replayer);
  MultiArmSimulator simulator(config.vehicle, scenario);
  simulator.Run(&wire);
  sink.Close();
  const Output out = ReadOutput(path, channels);
  ASSERT_GE(out.learned.size(), 39u);  // 8 s at 5 Hz
  ExpectStrainNoiseAsFlown(out, sink.snapshots, config.ekf.strain_noise_rad, 3);
  const std::string checksum = DescriptionChecksum(config.vehicle);
  for (size_t k = 0; k < out.learned.size(); ++k) {
    const estimator_learned_n_t& m = out.learned[k];
    ASSERT_EQ(m.n_arms, 3);
    ASSERT_EQ(m.tip_mass_kg.size(), 3u);
    EXPECT_EQ(m.vehicle_checksum, checksum);
    EXPECT_EQ(m.vehicle_checksum, out.statuses[k].vehicle_checksum);
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(m.strain_scale[i], 1.0);
      EXPECT_TRUE(std::isnan(m.strain_scale_std[i]));
      EXPECT_GT(m.tip_mass_std_kg[i], 0.0);
      EXPECT_NEAR(m.tip_mass_kg[i], 0.28812, 3.0 * m.tip_mass_std_kg[i] + 0.005);  // config/vehicles/trirotor.yaml
    }
    EXPECT_EQ(m.strain_scale_source, "params");
    EXPECT_EQ(m.tip_mass_source, "learned");
    EXPECT_EQ(m.body_mass_kg, 4.0);
    EXPECT_TRUE(std::isnan(m.body_mass_std_kg));
    EXPECT_EQ(m.body_mass_source, "params");
  }
  for (size_t i = 0; i < 3; ++i) {
    const double noise_rad = out.learned.back().strain_noise_rad[i];
    std::printf("gauge %zu: learned noise %.4g rad\n", i + 1, noise_rad);
    EXPECT_GT(noise_rad, std::sqrt(3.0) * 2e-5) << "arm " << i + 1;
    EXPECT_LT(noise_rad, std::sqrt(5.0) * 2e-5) << "arm " << i + 1;
  }
}

// tests/data/ekf_trace_input.lcm, recorded before estimator_learned_n_t
// existed: it replays, and the output carries the new message beside every
// ESTIMATOR_STATUS (no type of the log was changed).
TEST(EstimatorLearnedMessageTest, ALogRecordedBeforeTheTypeStillReplays) {
  const ChannelNames channels = MakeChannelNames();
  const std::string path = TempLog("old_log");
  RecordingSink<Replayer> sink(path, channels);
  Replayer replayer(EstimatorConfig(), ReplayOptions{}, &sink);
  std::string damage, error;
  ASSERT_TRUE(ReplayLogFile(SourceFile("tests/data/ekf_trace_input.lcm"), &replayer, &damage, &error)) << error;
  EXPECT_EQ(damage, "");
  sink.Close();
  EXPECT_EQ(replayer.stats().forces, 500);  // 4.75 s to 5.25 s at 1 kHz
  const Output out = ReadOutput(path, channels);
  EXPECT_EQ(out.learned.size(), 2u);  // 4.95 s and 5.15 s: every 0.2 s after the first sample
  for (const estimator_learned_n_t& m : out.learned) EXPECT_EQ(m.n_arms, 2);
}

}  // namespace
}  // namespace birotor
