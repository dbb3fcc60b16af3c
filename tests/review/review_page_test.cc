// The review page and the flight figures from a hand-made FlightData: the
// numbers of FlightSummaryText, and a page that names nothing on the network,
// carries dygraphs and one chart per kind of data present.
#include "review/review_page.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace birotor {
namespace {

FlightData MakeFlight() {
  FlightData d;
  d.path = "flight.lcm";
  d.events = 1000;
  d.duration_s = 1.0;
  d.truth = Table({"f1", "f2", "s1", "s2", "x", "z", "phi"});
  // x: 0 then +-0.003 m alternating (max |dev| 3 mm, rms 3 mm * sqrt(99/100)); z constant.
  for (int i = 0; i < 100; ++i)
    d.truth.Add(0.01 * i, {2.0, 2.0, 1.0, 1.0, i == 0 ? 0.0 : (i % 2 ? 0.003 : -0.003), 1.0, 0.0});
  d.motor_command = Table({"w1", "w2", "mode", "status"});
  // Fallback (bit 1) set on [0.2, 0.3) s and [0.7, 0.8) s: two rises. Mode 1 for 75 of 100.
  for (int i = 0; i < 100; ++i) {
    const bool fallback = (i >= 20 && i < 30) || (i >= 70 && i < 80);
    d.motor_command.Add(0.01 * i, {500.0, 500.0, i < 75 ? 1.0 : 0.0, fallback ? 1.0 : 0.0});
  }
  d.channels["BIROTOR_TRUTH"].messages = 100;
  d.channels["BIROTOR_MOTOR_COMMAND"].messages = 100;
  d.channels["BIROTOR_SETPOINT"].messages = 7;
  return d;
}

TEST(ReviewPageTest, FlightFigures) {
  const std::string text = FlightSummaryText(MakeFlight());
  EXPECT_NE(text.find("flight: 1000 events over 1.000 s\n"), std::string::npos) << text;
  // rms = 0.003 sqrt(99/100) = 0.002985 m.
  EXPECT_NE(text.find("position held (TRUTH, from t = 0.000 s): x max |dev| 0.0030 m, rms 0.0030 m; "
                      "z max |dev| 0.0000 m, rms 0.0000 m"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("100 MOTOR_COMMAND (75.0 % in force_feedback mode); 2 fallbacks at t [s] = 0.200, 0.700"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("flight: verdict: kept: altitude loss 0.000 m, max tilt 0.00 rad (TRUTH)"), std::string::npos)
      << text;
}

// A flight that fell below its SETPOINT altitude: the verdict says LOST with
// the time, against the setpoint (2 m) rather than the first altitude (1 m).
TEST(ReviewPageTest, LostFlightIsSaidInOneLine) {
  FlightData d = MakeFlight();
  d.setpoint = Table({"x ref", "z ref"});
  d.setpoint.Add(0.0, {0.0, 2.0});
  const std::string text = FlightSummaryText(d);
  EXPECT_NE(text.find("flight: verdict: LOST: altitude loss 1.000 m at t = 0.00 s;"), std::string::npos) << text;
  const std::string html = ReviewPageHtml(d);
  EXPECT_NE(html.find("<tr><th>lost</th><td class=alarm>yes, from 0.000 s (TRUTH)</td></tr>"), std::string::npos);
  EXPECT_NE(html.find("<tr><th>altitude loss</th><td>1.000 m at 0.000 s</td></tr>"), std::string::npos);
}

TEST(ReviewPageTest, SelfContainedPageWithTheChartsOfTheData) {
  const std::string html = ReviewPageHtml(MakeFlight());
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);
  EXPECT_EQ(html.find("href=\"http"), std::string::npos);
  EXPECT_NE(html.find("Dygraph"), std::string::npos);              // the library, inlined
  EXPECT_NE(html.find("\"id\":\"forces\""), std::string::npos);    // TRUTH forces
  EXPECT_NE(html.find("\"id\":\"position\""), std::string::npos);  // TRUTH x, z
  EXPECT_NE(html.find("\"id\":\"commands\""), std::string::npos);  // MOTOR_COMMAND
  EXPECT_EQ(html.find("\"id\":\"nis\""), std::string::npos);       // no ESTIMATOR_STATUS
  EXPECT_NE(html.find("fallbacks to the nominal law: 2 at t [s] = 0.200, 0.700"), std::string::npos);
  EXPECT_NE(html.find("<table id=headline>"), std::string::npos);
  EXPECT_NE(html.find("<li>No FORCE: this log holds no force estimate"), std::string::npos);  // said, not zeros
  EXPECT_NE(html.find("\"id\":\"attitude\""), std::string::npos);                             // TRUTH pitch
  EXPECT_NE(html.find("\"path\":{\"lines\":[{\"label\":\"truth\""), std::string::npos);
  // The fallbacks are markers through every chart.
  EXPECT_NE(html.find("\"events\":[{\"t\":0.2,\"kind\":\"fallback\",\"label\":\"fallback\"},"
                      "{\"t\":0.7,\"kind\":\"fallback\""),
            std::string::npos);
}

// Two logs on one page: a headline column each, series "A: ..." and "B: ..."
// on the same chart in different colours.
TEST(ReviewPageTest, TwoLogsOverlaid) {
  FlightData a = MakeFlight(), b = MakeFlight();
  b.path = "other.lcm";
  const std::string html = ReviewPageHtml(std::vector<const FlightData*>{&a, &b});
  EXPECT_NE(html.find("<th>A: flight.lcm</th><th>B: other.lcm</th>"), std::string::npos);
  EXPECT_NE(html.find("\"A: true force 1 [N]\",\"A: true force 2 [N]\",\"B: true force 1 [N]\""), std::string::npos);
  EXPECT_NE(html.find("\"colors\":[\"#000000\",\"#7f7f7f\",\"#9467bd\",\"#bcbd22\"]"), std::string::npos);
  EXPECT_NE(html.find("\"id\":\"controller_lanes_B\""), std::string::npos);
}

// Channel names with terminal escapes reach neither the page nor the summary raw.
TEST(ReviewPageTest, ControlCharactersInChannelNamesAreReplaced) {
  FlightData d = MakeFlight();
  d.channels["EVIL\x1b]0;owned\x07\x1b[2J"].messages = 1;
  const std::string html = ReviewPageHtml(d);
  EXPECT_EQ(html.find('\x1b'), std::string::npos);
  EXPECT_EQ(html.find('\x07'), std::string::npos);
  EXPECT_NE(html.find("<td>EVIL?]0;owned??[2J</td>"), std::string::npos);
}

}  // namespace
}  // namespace birotor
