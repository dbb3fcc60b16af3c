// The review page's headline from a hand-made flight: the rotor fault the
// estimator raised and the true thrust step, max tilt and altitude loss by the
// shared verdict (samples/flight_verdict.h), the VALID share, the fallbacks,
// the start-up FILTER_RESET kept out of the alarms, and the markers in order.
#include "review/flight_headline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "samples/samples.h"

namespace birotor {
namespace {

// 1 s at 100 Hz: FORCE CONVERGING|FILTER_RESET on the first row, VALID from
// row 10 (90 of 100), ROTOR2_FAULT from 0.52 s; TRUTH's rotor 2 thrust scale
// 1.00 -> 0.75 at 0.50 s, pitch up to 0.2 rad at 0.60 s, z 1 m with a 0.3 m
// dip at 0.70 s; MOTOR_COMMAND (force feedback) in the fallback on [0.00, 0.05)
// and [0.80, 0.90).
FlightData MakeFlight() {
  FlightData d;
  d.path = "flight.lcm";
  d.duration_s = 0.99;
  for (int i = 0; i < 100; ++i) {
    const double t = 0.01 * i;
    const int32_t status = i == 0   ? (kStatusConverging | kStatusFilterReset)
                           : i < 10 ? kStatusConverging
                                    : kStatusValid;
    const double rotor_faults = i >= 52 ? 2.0 : 0.0;  // bit 1: rotor 2
    d.force.Add(t, {20.0, 20.0, 0.1, 0.1, 1.0, i >= 52 ? 0.75 : 1.0, double(status), rotor_faults});
    d.truth.Add(t, {20.0, 20.0, 1.0, i >= 50 ? 0.75 : 1.0, 0.0, i == 70 ? 0.7 : 1.0, i == 60 ? -0.2 : 0.01});
    const bool fallback = i < 5 || (i >= 80 && i < 90);
    d.motor_command.Add(t, {500.0, 500.0, 1.0, fallback ? 1.0 : 0.0});
  }
  return d;
}

TEST(FlightHeadlineTest, AnswersTheQuestionsOfTheFirstScreen) {
  const FlightHeadline h = ComputeHeadline(MakeFlight());
  EXPECT_EQ(h.verdict_source, "TRUTH");
  EXPECT_FALSE(h.verdict.lost);  // 0.3 m loss < 0.5 m, 0.2 rad < 1 rad (FlightVerdictOptions)
  EXPECT_DOUBLE_EQ(h.verdict.max_tilt_rad, 0.2);
  EXPECT_DOUBLE_EQ(h.verdict.tilt_at_s, 0.6);
  EXPECT_NEAR(h.verdict.max_altitude_loss_m, 0.3, 1e-12);  // against the first altitude (no SETPOINT)
  EXPECT_EQ(h.force_estimates, 100);
  EXPECT_EQ(h.valid_estimates, 90);
  EXPECT_DOUBLE_EQ(h.first_valid_s, 0.1);
  EXPECT_EQ(h.rotor_fault_rises[0], 0);
  EXPECT_EQ(h.rotor_fault_rises[1], 1);
  // The controller starts in the fallback (no FORCE yet): not counted, as
  // ControllerHealth::fallbacks does not; the entry at 0.80 s is.
  EXPECT_EQ(h.fallbacks, 1);
  EXPECT_DOUBLE_EQ(h.force_used_s, 0.05);
  EXPECT_DOUBLE_EQ(h.startup_reset_s, 0.0);
  // Markers in time order; the start-up reset and fallback are none of them.
  ASSERT_EQ(h.events.size(), 3u);
  EXPECT_DOUBLE_EQ(h.events[0].t_s, 0.5);
  EXPECT_EQ(h.events[0].label, "rotor 2 thrust 1.00 -> 0.75");  // level over the first 0.5 s: rows 0..49 at 1.00
  EXPECT_EQ(h.events[1].label, "ROTOR2_FAULT");
  EXPECT_DOUBLE_EQ(h.events[1].t_s, 0.52);
  EXPECT_EQ(h.events[2].kind, "fallback");
  EXPECT_DOUBLE_EQ(h.events[2].t_s, 0.8);

  const std::string text = HeadlineText(h);
  EXPECT_NE(text.find("headline: lost: no (TRUTH)\n"), std::string::npos) << text;
  EXPECT_NE(text.find("headline: rotor faults: rotor 2 thrust 1.00 -> 0.75 at 0.500 s (TRUTH); ROTOR2_FAULT at "
                      "0.520 s\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("headline: max tilt: 0.200 rad (11.5 deg) at 0.600 s\n"), std::string::npos) << text;
  EXPECT_NE(text.find("headline: altitude loss: 0.300 m at 0.700 s\n"), std::string::npos) << text;
  EXPECT_NE(text.find("headline: FORCE VALID: 90.0 % (90 of 100 estimates)\n"), std::string::npos) << text;
  // 15 of 100 commands with FALLBACK_ACTIVE.
  EXPECT_NE(
      text.find("headline: fallbacks: 1 at 0.800 s; in the fallback in 15.0 % of MOTOR_COMMAND; FORCE flown on from "
                "0.050 s\n"),
      std::string::npos)
      << text;
  EXPECT_NE(text.find("headline: filter resets: none after the start-up reset\n"), std::string::npos) << text;
}

// A FILTER_RESET after the start is an alarm and a marker; a flight that fell
// 0.5 m below its SETPOINT is lost, marked where the verdict first said so.
TEST(FlightHeadlineTest, LaterResetAndLossAreAlarms) {
  FlightData d = MakeFlight();
  d.force.columns[d.ForceStatusColumn()][30] = kStatusValid | kStatusFilterReset;
  d.setpoint.Add(0.0, {0.0, 1.3});
  const FlightHeadline h = ComputeHeadline(d);
  EXPECT_TRUE(h.verdict.lost);
  EXPECT_NEAR(h.verdict.max_altitude_loss_m, 0.6, 1e-12);  // 1.3 m - 0.7 m at 0.70 s (0.3 m before)
  const std::string text = HeadlineText(h);
  EXPECT_NE(text.find("headline: lost: yes, from 0.700 s (TRUTH)\n"), std::string::npos) << text;
  EXPECT_NE(text.find("headline: filter resets: at 0.300 s\n"), std::string::npos) << text;
  EXPECT_EQ(h.events.back().kind, "fallback");  // 0.80 s
  bool lost_marked = false;
  for (const FlightEvent& e : h.events) lost_marked = lost_marked || (e.kind == "lost" && std::abs(e.t_s - 0.7) < 1e-9);
  EXPECT_TRUE(lost_marked);
}

// A simulator log without an estimator: no FORCE said in words, not a table of zeros.
TEST(FlightHeadlineTest, MissingDataIsSaid) {
  FlightData d = MakeFlight();
  d.force = FlightData().force;
  d.motor_command = FlightData().motor_command;
  const std::string text = HeadlineText(ComputeHeadline(d));
  EXPECT_NE(text.find("headline: rotor faults: rotor 2 thrust 1.00 -> 0.75 at 0.500 s (TRUTH)\n"), std::string::npos)
      << text;
  EXPECT_NE(text.find("headline: FORCE VALID: no FORCE in this log\n"), std::string::npos) << text;
  EXPECT_NE(text.find("headline: fallbacks: no MOTOR_COMMAND in this log\n"), std::string::npos) << text;
}

}  // namespace
}  // namespace birotor
