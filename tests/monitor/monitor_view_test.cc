// birotor-monitor's text: status words, progress bar, the plain line and the
// terminal block (fixed line count, so the redraw lands in place), with and
// without TRUTH, and the closing words.
#include "monitor/monitor_view.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

TEST(MonitorViewTest, StatusWords) {  // plot/status_words.h, shared with the plots
  EXPECT_EQ(StatusWords(0), "none");
  EXPECT_EQ(StatusWords(kStatusValid), "VALID");
  EXPECT_EQ(StatusWords(kStatusConverging | kStatusNoMotorInput), "CONVERGING|NO_MOTOR");
  EXPECT_EQ(StatusWords(kStatusValid | kStatusRotor2Fault), "VALID|ROTOR2_FAULT");
  EXPECT_EQ(StatusWords(kStatusInputStale | kStatusMeasurementRejected | kStatusFilterReset | kStatusRotor1Fault),
            "REJECTED|STALE|ROTOR1_FAULT|RESET");
  EXPECT_EQ(StatusWords(kStatusModelMismatch), "MODEL_MISMATCH");
  EXPECT_EQ(StatusWords(2048 | kStatusValid), "VALID|0x800");
  EXPECT_EQ(StatusWords(kStatusThrustDeficit | kStatusInputConflict), "THRUST_DEFICIT|CONFLICT");
}

TEST(MonitorViewTest, ProgressBar) {
  EXPECT_EQ(ProgressBar(0.0, 10.0, 10), "[----------]   0%");
  EXPECT_EQ(ProgressBar(5.0, 10.0, 10), "[#####-----]  50%");
  EXPECT_EQ(ProgressBar(12.0, 10.0, 10), "[##########] 100%");
  EXPECT_EQ(ProgressBar(3.3, 0.0, 10), "3.3 s");
}

void Feed(MonitorCollector* collector, const std::string& channel, const std::vector<uint8_t>& bytes) {
  collector->HandlePacket(channel, bytes.data(), bytes.size(), -1);
}

template <class Msg>
std::vector<uint8_t> Encode(const Msg& message) {
  std::vector<uint8_t> buffer;
  EncodeMessage(message, &buffer);
  return buffer;
}

TEST(MonitorViewTest, LinesShowTruthEstimateAndStatus) {
  const ChannelNames channels = MakeChannelNames();
  MonitorCollector collector(channels, 10.0);
  ViewContext context;
  context.scenario_duration_s = 10.0;
  EXPECT_NE(PlainViewLine(collector, context).find("waiting"), std::string::npos);
  const std::string empty_view = TerminalView(collector, context);
  EXPECT_EQ(std::count(empty_view.begin(), empty_view.end(), '\n'), kTerminalViewLines);

  TruthSample truth;
  truth.force_n[0] = 3.25;
  truth.force_n[1] = 3.5;
  truth.thrust_scale[1] = 0.75;
  Feed(&collector, channels.truth, Encode(ToMessage(truth)));
  truth.utime = 5000000;
  Feed(&collector, channels.truth, Encode(ToMessage(truth)));
  ForceEstimate estimate;
  estimate.utime = 5000000;
  estimate.force_n[0] = 3.2;
  estimate.force_n[1] = 3.6;
  estimate.thrust_scale[1] = 0.8;
  estimate.status = kStatusValid | kStatusRotor2Fault;
  Feed(&collector, channels.force, Encode(ToMessage(estimate)));

  const std::string line = PlainViewLine(collector, context);
  EXPECT_EQ(line.find('\x1b'), std::string::npos);
  EXPECT_NE(line.find("t=  5.00/10.00 s"), std::string::npos) << line;
  EXPECT_NE(line.find("50%"), std::string::npos) << line;
  EXPECT_NE(line.find("f1 true  3.250 est  3.200 ±0.000 N"), std::string::npos) << line;
  EXPECT_NE(line.find("mu2 0.750/0.800"), std::string::npos) << line;
  EXPECT_NE(line.find("VALID|ROTOR2_FAULT"), std::string::npos) << line;

  const std::string view = TerminalView(collector, context);
  EXPECT_EQ(std::count(view.begin(), view.end(), '\n'), kTerminalViewLines);
  EXPECT_NE(view.find("+0.100"), std::string::npos) << view;  // f2 error
  EXPECT_NE(view.find("no ESTIMATOR_STATUS yet"), std::string::npos) << view;
}

// issue 14: the vehicle view (no TRUTH) and the words "faults 0" next to
// ROTOR2_FAULT, which counted bad strain packets, not rotor faults.
TEST(MonitorViewTest, VehicleViewNamesFlagsWithTheirFirstTime) {
  const ChannelNames channels = MakeChannelNames();
  MonitorCollector collector(channels, 10.0);
  ViewContext context;
  context.truth_expected = false;
  EXPECT_NE(PlainViewLine(collector, context).find("waiting: FORCE 0 STATUS 0"), std::string::npos);

  ForceEstimate estimate;
  estimate.force_n[0] = 3.2;
  estimate.force_n[1] = 2.6;
  estimate.force_std_n[1] = 0.025;
  estimate.thrust_scale[1] = 0.76;
  estimate.status = kStatusValid | kStatusFilterReset;  // start-up
  Feed(&collector, channels.force, Encode(ToMessage(estimate)));
  estimate.utime = 2500000;
  estimate.seq = 1;
  estimate.status = kStatusValid | kStatusRotor2Fault;
  Feed(&collector, channels.force, Encode(ToMessage(estimate)));
  estimator_status_t status{};
  status.method = "ekf";
  status.resets = 1;
  status.last_reset_reason = "start";
  status.strain_nis_mean = 2.04;
  status.strain_gate = 30;
  for (const char* name : {"STRAIN", "MOTOR", "IMU", "POSE"}) {
    input_health_t input{};
    input.channel = name;
    input.received = 2;
    input.fused = 2;
    input.rate_hz = 1000;
    input.age_s = 0.0004;
    status.inputs.push_back(input);
  }
  status.inputs[0].rejected_gate = 3;
  status.inputs[3].age_s = 0.5;  // POSE stale
  status.num_inputs = 4;
  status.gauge_offset_rad[0] = 1.5e-5;
  status.gauge_offset_std_rad[0] = 2.7e-6;
  status.gauge_offset_source = "params";
  status.accelerometer.fused = 2;
  status.strain_scale[0] = 0.712;
  status.strain_scale[1] = 1.0;
  status.strain_scale_std[0] = 0.004;
  status.strain_scale_std[1] = 0.005;
  status.strain_scale_source = "learned";
  status.body_mass_kg = 4.0;
  status.body_mass_std_kg = std::numeric_limits<double>::quiet_NaN();  // not learned
  status.body_mass_source = "params";
  Feed(&collector, channels.estimator_status, Encode(status));

  const std::string line = PlainViewLine(collector, context);
  EXPECT_EQ(line.find("waiting"), std::string::npos) << line;
  EXPECT_EQ(line.find("true"), std::string::npos) << line;
  EXPECT_EQ(line.find("faults 0"), std::string::npos) << line;
  EXPECT_NE(line.find("t=  2.50 s"), std::string::npos) << line;  // since the first FORCE
  EXPECT_NE(line.find("f2  2.600 ±0.025 N"), std::string::npos) << line;
  EXPECT_NE(line.find("VALID|ROTOR2_FAULT  first alarms: ROTOR2_FAULT 2.500 s"), std::string::npos) << line;
  EXPECT_NE(line.find("strain 1000 Hz gate-rejected 3 bad packets 0"), std::string::npos) << line;

  const std::string view = TerminalView(collector, context);
  EXPECT_EQ(std::count(view.begin(), view.end(), '\n'), kTerminalViewLines);
  EXPECT_NE(view.find("(no TRUTH: vehicle view)"), std::string::npos) << view;
  EXPECT_NE(view.find("(rotor fault below 0.90)"), std::string::npos) << view;
  EXPECT_NE(view.find("strain NIS mean 2.04"), std::string::npos) << view;
  EXPECT_NE(view.find("resets 1 (last: start)"), std::string::npos) << view;
  EXPECT_NE(view.find("resets after start 0"), std::string::npos) << view;
  EXPECT_NE(view.find("STALE"), std::string::npos) << view;  // POSE 500 ms old > stale_age_s 0.1 s
  EXPECT_NE(view.find("learned: strain scale g 0.712 ±0.004 / 1.000 ±0.005 (learned)  body mass 4.000 kg (params)"),
            std::string::npos)
      << view;

  const std::string summary = VehicleSummaryText(collector);
  EXPECT_NE(summary.find("FORCE 2 messages over 2.50 s"), std::string::npos) << summary;
  EXPECT_NE(summary.find("VALID 100.0 %"), std::string::npos) << summary;
  EXPECT_NE(summary.find("first alarms: ROTOR2_FAULT 2.500 s"), std::string::npos) << summary;
  EXPECT_NE(summary.find("estimator ekf: resets 1 (last: start); strain NIS over the run mean 2.04"), std::string::npos)
      << summary;
  EXPECT_NE(summary.find("gauge offsets 1.50e-05 / 0.00e+00 rad +- 2.7e-06 / 0.0e+00 (from params, learned in flight); "
                         "accelerometer: fused 2"),
            std::string::npos)
      << summary;
  EXPECT_NE(summary.find("learned: strain scale g 0.712 ±0.004"), std::string::npos) << summary;
  EXPECT_EQ(DeliveryNote(collector), "");
}

TEST(MonitorViewTest, DeliveryNoteSeparatesUpstreamFaultsFromLostPackets) {
  const ChannelNames channels = MakeChannelNames();
  MonitorCollector collector(channels, 10.0);
  ForceEstimate estimate;
  for (int seq : {0, 1, 2, 6, 7}) {  // 3 missing
    estimate.seq = seq;
    estimate.utime = 1000 * seq;
    Feed(&collector, channels.force, Encode(ToMessage(estimate)));
  }
  estimator_status_t status{};
  input_health_t strain{};
  strain.channel = "STRAIN";
  strain.missing_samples = 2;  // the estimator itself missed 2
  status.inputs.push_back(strain);
  status.num_inputs = 1;
  Feed(&collector, channels.estimator_status, Encode(status));
  const std::string note = DeliveryNote(collector);
  EXPECT_NE(note.find("FORCE seq: 1 gaps, 3 messages missing"), std::string::npos) << note;
  EXPECT_NE(note.find("reports 2 strain samples missing"), std::string::npos) << note;
  EXPECT_NE(note.find("about 1 FORCE messages were lost"), std::string::npos) << note;
}

TEST(MonitorViewTest, DeliveryNoteNamesTwoForcePublishersInsteadOfMissingMessages) {
  const ChannelNames channels = MakeChannelNames();
  MonitorCollector collector(channels, 10.0);
  ForceEstimate estimate;
  // The daemon's stream near 50 and a replayed log's near 10000, interleaved.
  for (int i = 0; i < 5; ++i) {
    for (int seq : {50 + i, 10000 + i}) {
      estimate.seq = seq;
      estimate.utime = 1000 * i;
      Feed(&collector, channels.force, Encode(ToMessage(estimate)));
    }
  }
  const std::string note = DeliveryNote(collector);
  EXPECT_NE(note.find("FORCE comes from more than one publisher: seq went back 4 times"), std::string::npos) << note;
  EXPECT_EQ(note.find("missing"), std::string::npos) << note;
}

TEST(MonitorViewTest, SummaryNamesEveryFigure) {
  EvalResult result;
  result.rotor[0].mae_n = 0.05;
  result.step_rotor = 2;
  result.step_time_s = 8.0;
  result.detection_delay_s = 0.12;
  const std::string text = SummaryText(result);
  EXPECT_NE(text.find("rotor 1: MAE 0.0500 N"), std::string::npos) << text;
  EXPECT_NE(text.find("detected after 120 ms"), std::string::npos) << text;
}

// Issue 37: the strings of an ESTIMATOR_STATUS come off the wire; an escape
// sequence in them (retitle the terminal, clear the screen, ring the bell)
// must not reach the terminal raw. Each control character becomes '?'.
TEST(MonitorViewTest, WireStringsReachTheTerminalWithoutControlCharacters) {
  estimator_status_t status{};
  status.method = "ekf\x1b]0;owned\x07";
  status.strain_scale_source = "learned\x1b[2J";
  status.body_mass_source =
      "params\r\xc2\x9b"
      "31m";  // CR and the C1 CSI (U+009B) in UTF-8
  const std::string line = LearnedLine(status);
  EXPECT_EQ(line.find_first_of("\x1b\x07\r"), std::string::npos) << line;
  EXPECT_NE(line.find("(learned?[2J)"), std::string::npos) << line;
  EXPECT_NE(line.find("(params??31m)"), std::string::npos) << line;
  status.last_reset_reason = "start\x1b]0;owned\x07";
  status.gauge_offset_source = "tare\x1b]0;owned\x07";
  MonitorCollector collector(MakeChannelNames(), 10.0);
  Feed(&collector, "BIROTOR_ESTIMATOR_STATUS", Encode(status));
  ASSERT_TRUE(collector.has_status());
  for (const std::string& text : {VehicleSummaryText(collector), TerminalView(collector, ViewContext{}),
                                  PlainViewLine(collector, ViewContext{})}) {
    EXPECT_EQ(text.find("\x1b]"), std::string::npos) << text;  // the view's own ESC[K stays
    EXPECT_EQ(text.find('\x07'), std::string::npos) << text;
  }
}

}  // namespace
}  // namespace birotor
