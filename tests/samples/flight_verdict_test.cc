// Tests of samples/flight_verdict.h: the one definition of a lost flight.
#include "samples/flight_verdict.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace birotor {
namespace {

constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();

TEST(FlightVerdictTest, AHoverThatHoldsIsKept) {
  FlightJudge judge;
  for (int k = 0; k < 1000; ++k) judge.Add(1e-3 * k, 0.01 * std::sin(k * 0.01), 0.0, 0.02, 0.0, kUnknown);
  const FlightVerdict v = judge.Result();
  EXPECT_FALSE(v.lost);
  EXPECT_EQ(v.samples, 1000);
  EXPECT_NEAR(v.max_altitude_loss_m, 0.01, 1e-4);
  EXPECT_DOUBLE_EQ(v.max_tilt_rad, 0.02);
  EXPECT_EQ(v.Line(), "kept: altitude loss 0.010 m, max tilt 0.02 rad");
}

// The demo's failure before the real-time settings: the vehicle fell 28.6 m.
TEST(FlightVerdictTest, AFallIsLostWithItsTime) {
  FlightJudge judge;
  for (int k = 0; k <= 300; ++k) {
    const double t = 0.01 * k;
    judge.Add(t, t < 1.0 ? 0.0 : -28.6 * (t - 1.0) / 2.0, 0.0, 0.1, kUnknown, kUnknown);
  }
  const FlightVerdict v = judge.Result();
  EXPECT_TRUE(v.lost);
  EXPECT_NEAR(v.max_altitude_loss_m, 28.6, 1e-9);
  EXPECT_NEAR(v.altitude_loss_at_s, 3.0, 1e-9);
  EXPECT_EQ(v.Line().rfind("LOST: altitude loss 28.600 m at t = 3.00 s;", 0), 0u) << v.Line();
}

TEST(FlightVerdictTest, ATumbleIsLostEvenAtAltitude) {
  FlightJudge judge;
  judge.Add(0.0, 1.0, 1.0, 0.0, 0.0, kUnknown);
  judge.Add(0.5, 1.0, 1.0, 1.2, 0.0, kUnknown);  // beyond lost_tilt_rad 1.0
  EXPECT_TRUE(judge.Result().lost);
  EXPECT_NEAR(judge.Result().tilt_at_s, 0.5, 1e-12);
}

// A controlled descent after a loss the rotors cannot hover with: it ends
// on the ground at 0.9 m/s, far below the reference, and keeps the vehicle.
TEST(FlightVerdictTest, ASoftLandingIsKept) {
  FlightJudge judge;
  for (int k = 0; k <= 200; ++k) {
    const double z = std::max(1.0 - 0.9 * 0.01 * k, 0.0);
    judge.Add(0.01 * k, z, 1.0, 0.05, z > 0.0 ? -0.9 : 0.0, 0.0);
  }
  const FlightVerdict v = judge.Result();
  EXPECT_FALSE(v.lost) << v.Line();
  EXPECT_NEAR(v.ground_speed_m_s, 0.9, 1e-12);
  EXPECT_NE(v.Line().find("landed at 0.90 m/s"), std::string::npos) << v.Line();
}

TEST(FlightVerdictTest, AHardHitOfTheGroundIsLost) {
  FlightJudge judge;
  judge.Add(0.0, 0.5, 1.0, 0.0, -5.0, 0.0);
  judge.Add(0.1, 0.0, 1.0, 0.3, -5.0, 0.0);  // 5 m/s > ground_hit_speed_m_s 2
  const FlightVerdict v = judge.Result();
  EXPECT_TRUE(v.lost);
  EXPECT_TRUE(v.ground_hit);
  EXPECT_NE(v.Line().find("ground hit at 5.0 m/s"), std::string::npos) << v.Line();
}

// A gap in the track (NaN) is not a verdict; without any sample the verdict
// says so instead of "kept".
TEST(FlightVerdictTest, GapsAreSkippedAndNoTrackIsUnknown) {
  FlightJudge judge;
  EXPECT_EQ(judge.Result().Line(), "unknown: no position in the log");
  judge.Add(0.0, kUnknown, 0.0, 0.0, 0.0, kUnknown);
  judge.Add(0.1, 0.0, 0.0, kUnknown, 0.0, kUnknown);
  EXPECT_EQ(judge.Result().samples, 0);
  judge.Add(0.2, 0.0, kUnknown, 0.0, 0.0, kUnknown);  // no reference: the first altitude
  judge.Add(0.3, -0.6, kUnknown, 0.0, 0.0, kUnknown);
  EXPECT_TRUE(judge.Result().lost);
}

}  // namespace
}  // namespace birotor
