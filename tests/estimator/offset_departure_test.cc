// The offset-departure test (estimator/offset_departure.h, docs/mismatch.md
// "Offsets that took a force"): the formula on hand-made offsets, then the
// flights it is for: a payload the file lacks (body +10 %, airborne and from
// the ground) raised MODEL_MISMATCH ("mass") instead of VALID forces 1.96 N
// off, and the matching flights never near the limit. Seed 1, the shipped
// config/estimator.yaml.
#include "estimator/offset_departure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "evaluation/mismatch_targets.h"
#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace testing_support {
namespace {

constexpr double kSign[2] = {-1.0, 1.0};  // the birotor's arms (kArmSign)
constexpr double kStd = 5e-5;             // the anchor's sigma per gauge [rad]
constexpr double kZeroDrift[2] = {0.0, 0.0};
constexpr int64_t kMs = 1000;

OffsetDepartureTest Anchored(const double* drift_psd_rad2_s = kZeroDrift) {
  OffsetDepartureTest test(4.0, 0.1, 2, kSign, drift_psd_rad2_s);
  const double zero[2] = {0, 0}, std_rad[2] = {kStd, kStd};
  test.Anchor(zero, std_rad);
  return test;
}

// z = sum_i d_i (o_i - a_i) / sqrt(sum_i s_a,i^2): 5 sigma along the common
// force, sustained 0.1 s, departs; the departure holds when the offsets come
// back and ends with the next anchor.
TEST(OffsetDeparture, ACommonForceBeyondTheLimitDepartsAndHoldsUntilTheNextAnchor) {
  OffsetDepartureTest test = Anchored();
  const double a = 5.0 * std::sqrt(2.0) * kStd / 2.0;  // per gauge, so that z = 5
  const double beyond[2] = {-a, a};
  int64_t t = 0;
  EXPECT_FALSE(test.Add(t, beyond, true));
  EXPECT_NEAR(test.state().z, 5.0, 1e-12);
  EXPECT_NEAR(test.state().statistic, 1.25, 1e-12);
  bool departed = false;
  for (t = kMs; t <= 100 * kMs; t += kMs) departed = test.Add(t, beyond, true) || departed;
  EXPECT_TRUE(departed);
  EXPECT_TRUE(test.state().departed);
  EXPECT_EQ(test.state().departed_utime, 100 * kMs);
  const double back[2] = {0, 0};
  EXPECT_FALSE(test.Add(t, back, true));
  EXPECT_TRUE(test.state().departed);  // the offsets keep what they took
  const double std_rad[2] = {kStd, kStd};
  test.Anchor(back, std_rad);
  EXPECT_FALSE(test.state().departed);
}

// Opposite offsets on the two gauges mirror a torque, not a common force:
// not this test's (the gyro weighs f1 - f2 through the known inertia).
TEST(OffsetDeparture, OffsetsAgainstTheCommonForceAreNotJudged) {
  OffsetDepartureTest test = Anchored();
  const double torque[2] = {10 * kStd, 10 * kStd};
  for (int64_t t = 0; t <= 500 * kMs; t += kMs) EXPECT_FALSE(test.Add(t, torque, true));
  EXPECT_NEAR(test.state().z, 0.0, 1e-12);
}

// Near the ground each gauge's own departure is judged as well: the torque
// pattern above, 5 sigma on each gauge, departs there after hold_s, named
// by its gauge, while in free flight away from the ground it is not judged.
TEST(OffsetDeparture, OneGaugesOwnDepartureIsJudgedNearTheGround) {
  OffsetDepartureTest test = Anchored();
  const double torque[2] = {5 * kStd, 5 * kStd};
  EXPECT_FALSE(test.Add(0, torque, true, /*near_ground=*/false));
  EXPECT_EQ(test.state().statistic, 0.0);
  EXPECT_EQ(test.state().arm, -1);
  bool departed = false;
  for (int64_t t = kMs; t <= 101 * kMs; t += kMs) departed = test.Add(t, torque, true, true) || departed;
  EXPECT_TRUE(departed);
  EXPECT_NEAR(test.state().arm_z, 5.0, 1e-12);
  EXPECT_NEAR(test.state().statistic, 1.25, 1e-12);
  EXPECT_NEAR(test.state().z, 0.0, 1e-12);
  EXPECT_EQ(test.state().departed_arm, 0);
  // On the ground (not free flight) nothing is judged.
  OffsetDepartureTest grounded = Anchored();
  for (int64_t t = 0; t <= 300 * kMs; t += kMs) EXPECT_FALSE(grounded.Add(t, torque, false, true));
}

// A run beyond the limit shorter than hold_s, or broken by the ground, does not depart.
TEST(OffsetDeparture, ABriefRunOrTheGroundDoesNotDepart) {
  OffsetDepartureTest test = Anchored();
  const double a = 6.0 * std::sqrt(2.0) * kStd / 2.0;
  const double beyond[2] = {-a, a}, within[2] = {0, 0};
  int64_t t = 0;
  for (; t < 90 * kMs; t += kMs) EXPECT_FALSE(test.Add(t, beyond, true));
  EXPECT_FALSE(test.Add(t, within, true));
  for (t += kMs; t < 180 * kMs; t += kMs) EXPECT_FALSE(test.Add(t, beyond, true));
  EXPECT_FALSE(test.Add(t, beyond, false));  // supported: not judged, the run restarts
  EXPECT_EQ(test.state().statistic, 0.0);
  for (t += kMs; t < 270 * kMs; t += kMs) EXPECT_FALSE(test.Add(t, beyond, true));
  EXPECT_FALSE(test.state().departed);
}

// The drift since the anchor widens the range: q t adds to the anchor's variance.
TEST(OffsetDeparture, TheDriftSinceTheAnchorWidensTheRange) {
  const double q[2] = {1e-10, 1e-10};  // [rad^2/s]
  OffsetDepartureTest test = Anchored(q);
  const double a = 1e-4;
  const double beyond[2] = {-a, a};
  test.Add(0, beyond, true);
  EXPECT_NEAR(test.state().z, 2 * a / std::sqrt(2 * kStd * kStd), 1e-9);
  test.Add(100'000'000, beyond, true);  // 100 s later
  EXPECT_NEAR(test.state().z, 2 * a / std::sqrt(2 * kStd * kStd + 2 * q[0] * 100.0), 1e-9);
}

TEST(OffsetDeparture, ALimitOfZeroSwitchesItOff) {
  OffsetDepartureTest test(0.0, 0.1, 2, kSign, kZeroDrift);
  const double far[2] = {-1.0, 1.0};
  for (int64_t t = 0; t <= 500 * kMs; t += kMs) EXPECT_FALSE(test.Add(t, far, true));
  EXPECT_FALSE(test.enabled());
  EXPECT_EQ(test.state().statistic, 0.0);
}

struct DepartureFlight {
  MismatchTargetFigures targets;
  ModelConsistencyState consistency;
};

// The gentle flight, seed 1, shipped files, with overrides; ground: the
// shipped ground phase and 19 s (as evaluation/mismatch_cases.cc).
DepartureFlight Fly(const std::string& name, std::vector<std::string> overrides, bool ground) {
  if (ground) overrides.insert(overrides.begin(), {"ground.enabled=true", "scenario.duration_s=19"});
  overrides.push_back("scenario.seed=1");
  const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile("gentle"), overrides), ReferenceConfig());
  DepartureFlight f;
  f.targets = EvaluateMismatchTargets(run.forces, run.truth, run.liftoff_utime, MismatchTargets());
  f.consistency = run.health.consistency;
  std::printf("%s: VALID %.3f, departed at %.3f s, peak |z| %.2f, mismatch %d (%s)\n", name.c_str(),
              f.targets.valid_share, f.consistency.offsets.departed_utime * 1e-6, f.consistency.offsets.peak_abs_z,
              f.consistency.mismatch, MismatchParameterName(f.consistency.parameter));
  return f;
}

// Body +10 % airborne: the offsets take Delta m g / 2 per rotor, 5.3 sigma
// along the common force within milliseconds; departed at 0.102 s, "mass",
// never VALID after 5 s (before: VALID 1.000, 1.959 N off, 2-sigma 0.000).
TEST(OffsetDepartureFlights, APayloadTheFileLacksIsRaisedNotPublished) {
  const DepartureFlight f = Fly("body +10 %, airborne", {"vehicle.body_mass_kg=4.4"}, false);
  EXPECT_TRUE(f.consistency.offsets.departed);
  EXPECT_LE(f.consistency.offsets.departed_utime, 200 * kMs);
  EXPECT_GT(f.consistency.offsets.peak_abs_z, 5.0);
  EXPECT_TRUE(f.consistency.mismatch);
  EXPECT_EQ(f.consistency.parameter, MismatchParameter::kMass);
  EXPECT_EQ(f.targets.valid_share, 0.0);
}

// From the ground: the tare anchors the offsets; the lift-off lets the
// payload into them (departed 0.23 s after the lift-off, peak 21 sigma).
TEST(OffsetDepartureFlights, APayloadAfterAGroundPhaseIsRaisedAfterTheLiftOff) {
  const DepartureFlight f = Fly("body +10 %, ground start", {"vehicle.body_mass_kg=4.4"}, true);
  EXPECT_TRUE(f.consistency.offsets.departed);
  EXPECT_TRUE(f.consistency.mismatch);
  EXPECT_EQ(f.targets.valid_share, 0.0);
}

// A payload within the limit (body +3 % and +5 %, airborne and from the
// ground): the test does not depart and the forces stay VALID, 0.59 / 0.98
// N off, but the departure's share beyond offset_departure_in_sigma_above
// is in each published sigma: 2-sigma share of the VALID estimates
// measured 0.967-1.000 (before: 0.000-0.011, the offsets took the payload
// and the sigma did not say so).
TEST(OffsetDepartureFlights, APayloadWithinTheLimitIsInTheSigma) {
  for (const char* mass : {"4.12", "4.2"}) {
    for (bool ground : {false, true}) {
      const DepartureFlight f = Fly(std::string("body ") + mass + " kg" + (ground ? ", ground start" : ""),
                                    {std::string("vehicle.body_mass_kg=") + mass}, ground);
      std::printf("  MAE %.3f N, 2-sigma share %.3f\n", f.targets.valid_mae_n, f.targets.two_sigma_share);
      EXPECT_FALSE(f.consistency.offsets.departed) << mass;
      EXPECT_GT(f.targets.valid_share, 0.9) << mass;
      EXPECT_GT(f.targets.valid_mae_n, 0.5) << mass;  // the payload's force: not learned
      EXPECT_GE(f.targets.two_sigma_share, 0.9) << mass;
    }
  }
}

// The matching vehicle, airborne and from the ground, and the changes the
// estimator explains (c_T -15 %, tip mass +20 %): never near the limit
// (peak |z| 0.28-0.70 measured; the limit is 4).
TEST(OffsetDepartureFlights, MatchingAndExplainedVehiclesStayWithinTheirOffsets) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"gentle", {}},
      {"c_T -15 %", {"vehicle.thrust_coeff_n_s2_rad2=3.91e-5"}},
      {"tip mass +20 %", {"vehicle.tip_mass_kg=0.345744"}},
  };
  for (const auto& [name, overrides] : cases) {
    for (bool ground : {false, true}) {
      const DepartureFlight f = Fly(name + (ground ? ", ground start" : ""), overrides, ground);
      EXPECT_FALSE(f.consistency.offsets.departed) << name;
      EXPECT_LT(f.consistency.offsets.peak_abs_z, 2.0) << name;
    }
  }
}

}  // namespace
}  // namespace testing_support
}  // namespace birotor
