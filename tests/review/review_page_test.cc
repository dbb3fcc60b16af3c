// The review page and the flight figures from a hand-made FlightData: the
// numbers of FlightSummaryText, and a page that names nothing on the network,
// carries dygraphs and one chart per kind of data present.
#include "review/review_page.h"

#include <gtest/gtest.h>

#include <string>

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
  EXPECT_NE(ReviewPageHtml(d).find("<p id=verdict class=lost><b>Verdict:</b> LOST: altitude loss 1.000 m"),
            std::string::npos);
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
  EXPECT_NE(html.find("BIROTOR_SETPOINT: 7 messages; this build of birotor-review does not draw SETPOINT"),
            std::string::npos);
}

}  // namespace
}  // namespace birotor
