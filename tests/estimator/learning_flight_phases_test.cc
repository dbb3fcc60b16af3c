// When a flight starts and ends while the strain scales learn
// (EkfOptions::learn_strain_scale, estimator/ekf_parameter_learning.cc):
// a start in the air, and a rotor loss in the air, which is no landing.
// Figures measured on the development VM (deterministic, fixed seeds);
// bounds leave room around them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "evaluation/mismatch_metrics.h"
#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace testing_support {
namespace {

int64_t ThrustStepUtime(const ScenarioRun& run) {
  for (const FaultEvent& f : run.faults) {
    if (f.kind == FaultKind::kThrustStep) return f.utime;
  }
  return -1;
}

double ValidShareFrom(const ScenarioRun& run, int64_t from_utime) {
  int64_t valid = 0, count = 0;
  for (const PairedSample& p : run.pairs) {
    if (p.utime < from_utime) continue;
    ++count;
    if (p.status & kStatusValid) ++valid;
  }
  return count > 0 ? static_cast<double>(valid) / static_cast<double>(count) : NAN;
}

// A rotor loss in the air: the total thrust estimate may fall below the
// free-flight criterion (half the weight) for a moment. Only a contact (or that thrust near the ground) ends a
// flight, so no new lift-off settling withholds VALID after the loss and
// the strain scales are not split again on the loss's aftermath.
// thrust_loss_severe: rotor 2 loses 40 % at 5 s in a hover on the vehicle
// the file describes. Measured: VALID 1.000 of the estimates from 0.1 s
// after the loss, g 1.0109 +- 0.0128 and 0.9961 +- 0.0110 at the end.
// Before, a loss ended the flight: VALID 0.958 (withheld 0.5 s after the
// loss, when force feedback needs it most) and g 1.046 / 0.959, the loss
// absorbed by the scales.
TEST(LearningFlightPhases, ALossInTheAirKeepsValidAndTheStrainScales) {
  const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile("thrust_loss_severe")), StrainScaleLearningConfig());
  const int64_t step_utime = ThrustStepUtime(run);
  ASSERT_GT(step_utime, 0);
  const double valid_share = ValidShareFrom(run, step_utime + 100000);
  const GaugeOffsetSample& last = run.gauge_offsets.back();
  std::printf("VALID from 0.1 s after the loss %.4f; g %.4f +- %.4f, %.4f +- %.4f; rotor 2 MAE %.4f N\n", valid_share,
              last.strain_scale[0], last.strain_scale_std[0], last.strain_scale[1], last.strain_scale_std[1],
              ForceMae(run, 1, step_utime + 100000));
  EXPECT_GE(valid_share, 0.98);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(last.strain_scale[i], 1.0, 0.02) << "arm " << i + 1;
    EXPECT_LE(std::abs(last.strain_scale[i] - 1.0), 2.0 * last.strain_scale_std[i]) << "arm " << i + 1;
  }
}

}  // namespace
}  // namespace testing_support
}  // namespace birotor

namespace birotor {
namespace testing_support {
namespace {

double FirstValidS(const ScenarioRun& run) {
  for (const ForceEstimate& e : run.forces) {
    if (e.status & kStatusValid) return (e.utime - run.forces.front().utime) * 1e-6;
  }
  return NAN;
}

// A start in the air: the strain scales and the gauge offsets settle for
// slow_learning_delay_s, and VALID waits only while an offset moved beyond
// settling_offset_limit_sigma (a payload's forces sit there then). The
// vehicle the file describes is VALID from its first estimates (measured
// 0.006 s; 0.5 s when the whole settling waited).
TEST(LearningFlightPhases, AStartInTheAirOnTheFilesVehicleIsValidAtOnce) {
  const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile("gentle")), StrainScaleLearningConfig());
  const double first_valid_s = FirstValidS(run);
  std::printf("gentle: first VALID at %.3f s\n", first_valid_s);
  EXPECT_LE(first_valid_s, 0.1);
}

// Body +10 % airborne from the start (a payload the gauges' tare never
// saw): its offsets move at once, VALID waits, and no 2 s window of VALID
// estimates is dishonest. Seeds 8 and 9 published 1.96 N off for 0.5 s
// when nothing waited (worst window share 0.000); with a 3 sigma limit seed
// 8 still did. Measured with 2: worst window 1.000 on both.
TEST(LearningFlightPhases, APayloadAtAStartInTheAirWaitsForTheOffsets) {
  for (const char* seed : {"scenario.seed=8", "scenario.seed=9"}) {
    const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile("gentle"), {"vehicle.body_mass_kg=4.4", seed}),
                                        StrainScaleLearningConfig());
    const double worst = EvaluateMismatch(run.forces, run.truth, MismatchEvalOptions()).worst_valid_window_share;
    std::printf("body +10 %%, %s: worst 2 s window of VALID %.3f\n", seed, worst);
    EXPECT_GE(worst, 0.80) << seed;
  }
}

}  // namespace
}  // namespace testing_support
}  // namespace birotor
