// A rotor loss in the air while the strain scales learn
// (EkfOptions::learn_strain_scale, estimator/ekf_parameter_learning.cc
// UpdateLearning): the total thrust estimate falls below the weight for a
// while, which is no landing. Only a contact ends a flight, so no new
// lift-off settling withholds VALID after the loss and the strain scales are
// not split again on the loss's aftermath. Measured on the development VM
// (deterministic, the scenario's seed): VALID 1.000 of the estimates from
// 0.1 s after the loss, g 1.0109 +- 0.0128 and 0.9961 +- 0.0110 at the end.
// Before, a loss ended the flight: VALID 0.958 (withheld 0.5 s after the
// loss, when force feedback needs it most) and g 1.046 / 0.959, the loss
// absorbed by the scales.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

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

// thrust_loss_severe: rotor 2 loses 40 % at 5 s in a hover on the vehicle
// the file describes.
TEST(LearningRotorLoss, StaysValidAndKeepsTheStrainScalesAfterALossInTheAir) {
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
