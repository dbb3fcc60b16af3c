// birotor-monitor's text: status words, progress bar, the plain line and the
// terminal block (fixed line count, so the redraw lands in place).
#include "monitor/monitor_view.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

TEST(MonitorViewTest, StatusWords) {
  EXPECT_EQ(StatusWords(0), "none");
  EXPECT_EQ(StatusWords(kStatusValid), "VALID");
  EXPECT_EQ(StatusWords(kStatusConverging | kStatusNoMotorInput), "CONVERGING|NO_MOTOR");
  EXPECT_EQ(StatusWords(kStatusValid | kStatusRotor2Fault), "VALID|ROTOR2_FAULT");
  EXPECT_EQ(StatusWords(kStatusInputStale | kStatusMeasurementRejected | kStatusFilterReset | kStatusRotor1Fault),
            "REJECTED|STALE|ROTOR1_FAULT|RESET");
  EXPECT_EQ(StatusWords(256 | kStatusValid), "VALID|0x100");
}

TEST(MonitorViewTest, ProgressBar) {
  EXPECT_EQ(ProgressBar(0.0, 10.0, 10), "[----------]   0%");
  EXPECT_EQ(ProgressBar(5.0, 10.0, 10), "[#####-----]  50%");
  EXPECT_EQ(ProgressBar(12.0, 10.0, 10), "[##########] 100%");
  EXPECT_EQ(ProgressBar(3.3, 0.0, 10), "3.3 s");
}

void Feed(MonitorCollector* collector, const std::string& channel, const std::vector<uint8_t>& bytes) {
  collector->HandlePacket(channel, bytes.data(), bytes.size());
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
  EXPECT_NE(line.find("f1 true  3.250 est  3.200 N"), std::string::npos) << line;
  EXPECT_NE(line.find("mu2 0.750/0.800"), std::string::npos) << line;
  EXPECT_NE(line.find("VALID|ROTOR2_FAULT"), std::string::npos) << line;

  const std::string view = TerminalView(collector, context);
  EXPECT_EQ(std::count(view.begin(), view.end(), '\n'), kTerminalViewLines);
  EXPECT_NE(view.find("+0.100"), std::string::npos) << view;  // f2 error
  EXPECT_NE(view.find("(no status yet)"), std::string::npos) << view;
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

}  // namespace
}  // namespace birotor
