// The mismatch scenarios of config/scenarios (issue 27 item 4) through the
// pipeline with the reference file: when STATUS_MODEL_MISMATCH rises, which
// parameter it names, how many estimates were VALID before (the fast test),
// and no flag on the matching-file scenarios. Figures
// measured on the development VM (docs/mismatch.md); bounds at most 1.5x.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "evaluation/mismatch_targets.h"
#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace testing_support {
namespace {

struct MismatchFigures {
  double raised_s = -1;  // first MODEL_MISMATCH after the first estimate [s]; -1 never
  int64_t mismatch = 0, valid = 0, deficit = 0, estimates = 0;
  std::string parameter;
  bool raised_fast = false;
  double fast_cusum_peak = 0;  // the fast test's largest CUSUM (limit 30) [1]
};

MismatchFigures Fly(const std::string& name, const std::vector<std::string>& overrides = {}) {
  const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile(name), overrides), ReferenceConfig());
  MismatchFigures f;
  const int64_t start = run.forces.front().utime;
  for (const ForceEstimate& e : run.forces) {
    ++f.estimates;
    if (e.status & kStatusValid) ++f.valid;
    if (e.status & kStatusThrustDeficit) ++f.deficit;
    if (e.status & kStatusModelMismatch) {
      if (f.raised_s < 0) f.raised_s = (e.utime - start) * 1e-6;
      ++f.mismatch;
    }
  }
  f.parameter = MismatchParameterName(run.health.consistency.parameter);
  f.raised_fast = run.health.consistency.raised_fast;
  f.fast_cusum_peak = run.health.consistency.fast_cusum_peak;
  std::printf("%s: raised %.3f s (fast %d), %s, mismatch %lld valid %lld deficit %lld of %lld, CUSUM peak %.1f\n",
              name.c_str(), f.raised_s, f.raised_fast ? 1 : 0, f.parameter.c_str(), static_cast<long long>(f.mismatch),
              static_cast<long long>(f.valid), static_cast<long long>(f.deficit), static_cast<long long>(f.estimates),
              f.fast_cusum_peak);
  return f;
}

// The fast test's CUSUM stays below its limit (30) with the margin measured:
// a rotor's thrust step and a lift-off put the accelerometer at its gate for
// a few samples only.
TEST(MismatchScenarios, MatchingFileNeverRaises) {
  struct Case {
    const char* name;
    double fast_cusum_peak;  // measured
  };
  for (const Case& c : {Case{"gentle", 1.8}, Case{"thrust_loss_severe", 15.9}, Case{"gauge_drift", 6.0},
                        Case{"gauge_offset", 11.0}, Case{"sensor_faults", 2.1}}) {
    const MismatchFigures f = Fly(c.name);
    EXPECT_EQ(f.mismatch, 0) << c.name;
    EXPECT_EQ(f.parameter, "") << c.name;
    EXPECT_LE(f.fast_cusum_peak, 1.5 * c.fast_cusum_peak) << c.name;
  }
}

// The gentle flight from the ground (3 s rest, 1 s spool-up) on the
// matching vehicle, seeds 1-5: never raised. Seed 1 lost the EKF's pitch
// rate at the lift-off (the gyro gated in runs of up to 188) and raised
// `mass` at 5.0 s before the EKF took it back (gyro_liftoff_recovery_s).
TEST(MismatchScenarios, MatchingFileFromTheGroundNeverRaises) {
  for (int seed = 1; seed <= 5; ++seed) {
    const MismatchFigures f =
        Fly("gentle", {"ground.enabled=true", "scenario.duration_s=19", "scenario.seed=" + std::to_string(seed)});
    EXPECT_EQ(f.mismatch, 0) << "seed " << seed;
    EXPECT_EQ(f.parameter, "") << "seed " << seed;
  }
}

// The aggressive move from the ground, seeds 1-5: the move ends during the
// rest, so the vehicle lifts off towards a target 1.4 m away with rotor 1
// about 9 N above rotor 2 and pitches at once. The strain gate rejects in
// that spin-up and the gyro, gated, lost the pitch rate: `mass` raised
// 0.39-0.41 s after the lift-off on 10 of 10 seeds until the lift-off rule
// also held inside the lift-off's own thrust step (its first step_hold_s).
TEST(MismatchScenarios, AggressiveLiftOffNeverRaises) {
  for (int seed = 1; seed <= 5; ++seed) {
    const MismatchFigures f =
        Fly("aggressive", {"ground.enabled=true", "scenario.duration_s=12", "scenario.seed=" + std::to_string(seed)});
    EXPECT_EQ(f.mismatch, 0) << "seed " << seed;
    EXPECT_EQ(f.parameter, "") << "seed " << seed;
  }
}

// Hovering at the ground's height (hover with the ground phase: the
// setpoint z = 0 keeps the body brushing the ground with a support below
// the contact's threshold), seeds 1-10. Without the may-touch band
// (ground_may_touch_m 0) MODEL_MISMATCH was raised on seeds 2, 5, 6, 7, 8
// and 10 (at 2.9-15.6 s: the touches moved the gauge offsets) and the
// 2-sigma share after 5 s was 0.77-0.87 (worst 2 s window 0.16-0.68).
// With it (the shipped 0.02 m, from 0.5 s after the let-go), as measured
// here from 5 s after the lift-off: never raised, VALID 1.000, MAE of the
// worse rotor 0.110-0.153 N (the support is unknown there; airborne 0.07),
// 2-sigma 0.966-0.992, worst 2 s window 0.855-0.972 (docs/estimator.md,
// "Hovering at the ground's height").
TEST(MismatchScenarios, HoverAtTheGroundsHeightNeverRaises) {
  for (int seed = 1; seed <= 10; ++seed) {
    const ScenarioRun run = RunScenario(
        LoadScenario(ScenarioFile("hover"), {"ground.enabled=true", "scenario.seed=" + std::to_string(seed)}),
        ReferenceConfig());
    const MismatchTargetFigures f =
        EvaluateMismatchTargets(run.forces, run.truth, run.liftoff_utime, MismatchTargets());
    std::printf("hover at the ground's height, seed %d: VALID %.3f, MAE %.3f N, 2-sigma %.3f, window %.3f\n", seed,
                f.valid_share, f.valid_mae_n, f.two_sigma_share, f.worst_window_share);
    int64_t mismatch = 0;
    for (const ForceEstimate& e : run.forces) mismatch += (e.status & kStatusModelMismatch) != 0;
    EXPECT_EQ(mismatch, 0) << "seed " << seed;
    EXPECT_EQ(f.valid_share, 1.0) << "seed " << seed;
    EXPECT_GE(f.two_sigma_share, 0.93) << "seed " << seed;
    EXPECT_GE(f.worst_window_share, 0.80) << "seed " << seed;
    EXPECT_LT(f.valid_mae_n, 0.2) << "seed " << seed;
  }
}

TEST(MismatchScenarios, PayloadIsMass) {
  for (const char* name : {"mismatch_payload_plus15", "mismatch_payload_minus15"}) {
    const MismatchFigures f = Fly(name);
    EXPECT_GE(f.raised_s, 0.0) << name;
    EXPECT_TRUE(f.raised_fast) << name;
    EXPECT_LE(f.raised_s, 0.0165) << name;  // measured 0.011 s (the fast test; the windows: 0.50 s)
    EXPECT_EQ(f.parameter, "mass") << name;
    EXPECT_LE(f.valid, 6) << name;  // before the raise only (measured 4; 493 with the windows alone)
    EXPECT_EQ(f.deficit, 0) << name;
  }
}

TEST(MismatchScenarios, StiffArmAndGaugeScaleAreStiffnessOrGaugeScale) {
  for (const char* name : {"mismatch_stiffness_plus20", "mismatch_stiffness_minus20", "mismatch_gauge_scale_0p7",
                           "mismatch_gauge_scale_1p3"}) {
    const MismatchFigures f = Fly(name);
    EXPECT_GE(f.raised_s, 0.0) << name;
    EXPECT_TRUE(f.raised_fast) << name;
    EXPECT_LE(f.raised_s, 0.0165) << name;  // measured 0.011 s
    EXPECT_EQ(f.parameter, "stiffness_or_gauge_scale") << name;
    EXPECT_LE(f.valid, 6) << name;  // measured 4
    EXPECT_EQ(f.deficit, 0) << name;
  }
}

TEST(MismatchScenarios, AllAtOnceWithinOneSecond) {
  const MismatchFigures f = Fly("mismatch_all");
  EXPECT_GE(f.raised_s, 0.0);
  EXPECT_TRUE(f.raised_fast);
  EXPECT_LE(f.raised_s, 0.0165);  // measured 0.011 s (0.75 s with the windows alone); the bound 1 s
  EXPECT_EQ(f.parameter, "stiffness_or_gauge_scale");
  EXPECT_LE(f.valid, 4);  // before the raise only (measured 3; 742 with the windows alone)
  EXPECT_EQ(f.deficit, 0);
}

TEST(MismatchScenarios, MotorLagAndThrustMapAreLearnedNotRaised) {
  for (const char* name : {"mismatch_motor_lag_plus30", "mismatch_thrust_coeff_plus20"}) {
    const MismatchFigures f = Fly(name);
    EXPECT_EQ(f.mismatch, 0) << name;
    EXPECT_EQ(f.deficit, 0) << name;
  }
}

}  // namespace
}  // namespace testing_support
}  // namespace birotor
