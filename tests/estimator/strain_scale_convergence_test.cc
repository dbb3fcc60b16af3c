// The learned strain scale g_i against the flown vehicle's value over time
// (issue 27, estimator/ekf_parameter_learning.cc: the split of scale and
// offset again once the fast states settled, and the published sigma;
// docs/mismatch.md "Online learning of the slow parameters"): on the
// mismatch family (gauge scale 0.7 / 1.3 on arm 1, both arms 20 % stiffer or
// softer) g_i converges toward the truth and the published sigma covers the
// error. Figures measured on the development VM with the shipped
// config/estimator.yaml plus learn_strain_scale; bounds at most 1.5x.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace testing_support {
namespace {

// The published g_i at 2, 5, 10 and 15 s of the scenario (the last sample).
struct Trace {
  double g[4][2] = {};
  double std[4][2] = {};
};
constexpr double kTimesS[4] = {2.0, 5.0, 10.0, 15.0};

Trace Fly(const char* name, const double g_true[2]) {
  const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile(name)), StrainScaleLearningConfig());
  const int64_t start = run.gauge_offsets.front().utime;
  Trace trace;
  int k = 0;
  for (size_t n = 0; n < run.gauge_offsets.size() && k < 4; ++n) {
    const GaugeOffsetSample& s = run.gauge_offsets[n];
    if (s.utime - start < kTimesS[k] * 1e6 && n + 1 < run.gauge_offsets.size()) continue;
    std::printf("%s %5.1f s:", name, kTimesS[k]);
    for (int i = 0; i < 2; ++i) {
      trace.g[k][i] = s.strain_scale[i];
      trace.std[k][i] = s.strain_scale_std[i];
      std::printf("  g%d %.4f +- %.4f (%+.1f sigma)", i + 1, s.strain_scale[i], s.strain_scale_std[i],
                  (s.strain_scale[i] - g_true[i]) / s.strain_scale_std[i]);
    }
    std::printf("\n");
    ++k;
  }
  EXPECT_EQ(k, 4) << name;
  return trace;
}

// A gauge reading 0.7 or 1.3 of the file's scale on arm 1. Measured: within
// 0.9 published sigma at 2, 5, 10 and 15 s on both arms (g_1 0.7063 +-
// 0.0218 at 2 s, 0.6973 +- 0.0113 at 15 s; 1.2945 +- 0.0225, 1.2977 +-
// 0.0113); before the split (issue 27) 0.92 / 0.83 +- 0.01, 17-25 sigmas.
TEST(StrainScaleConvergence, AGaugeScaleIsLearnedWithAnHonestSigma) {
  for (const double scale : {0.7, 1.3}) {
    const double g_true[2] = {scale, 1.0};
    const Trace t = Fly(scale < 1 ? "mismatch_gauge_scale_0p7" : "mismatch_gauge_scale_1p3", g_true);
    for (int k = 0; k < 4; ++k) {
      for (int i = 0; i < 2; ++i) {
        EXPECT_LE(std::abs(t.g[k][i] - g_true[i]), 1.5 * t.std[k][i]) << scale << " " << kTimesS[k];  // 0.9
      }
    }
    EXPECT_NEAR(t.g[3][0], scale, 0.02);  // measured 0.0027 / 0.0023 off; bound the 0.02 resolution
    EXPECT_LT(t.std[3][0], 0.017);        // useful too: 1.5 x the measured 0.0113
  }
}

// Both arms 20 % stiffer: g = 0.833. A stiffer arm is not only a smaller
// static reading (its mode and the hinge force the accelerometer sees move
// too): g stops near 0.90 and the offsets keep 1.2e-4 rad, which the
// published sigma takes in. Measured: 0.7-1.0 sigma at every time (0.8961
// +- 0.0629 / 0.8996 +- 0.0664 at 15 s; before: 0.940 +- 0.0076, 14 sigmas).
TEST(StrainScaleConvergence, AStifferArmIsCoveredByItsSigma) {
  const double g_true[2] = {1 / 1.2, 1 / 1.2};
  const Trace t = Fly("mismatch_stiffness_plus20", g_true);
  for (int k = 0; k < 4; ++k) {
    for (int i = 0; i < 2; ++i) EXPECT_LE(std::abs(t.g[k][i] - g_true[i]), 1.5 * t.std[k][i]) << kTimesS[k];  // 1.0
  }
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(t.g[3][i], g_true[i], 0.1);  // 1.5 x the measured 0.063 / 0.066
}

// Both arms 20 % softer: g = 1.25, 2.5 prior sigmas. The accelerometer's
// gate opens the strain scales when every sample lands at it
// (GateInflation::kAccelerometer; before, g crept up over 15 s with
// MODEL_MISMATCH raised throughout: 1.0813 +- 0.0335 at 2 s, 5.0 sigmas).
// Measured: within 0.9 sigma at every time (1.2404 +- 0.0248 / 1.2579 +-
// 0.0234 at 2 s, 1.2654 +- 0.0190 / 1.2782 +- 0.0306 at 15 s).
TEST(StrainScaleConvergence, ASofterArmIsLearnedOnceTheAccelerometerOpensTheScales) {
  const double g_true[2] = {1 / 0.8, 1 / 0.8};
  const Trace t = Fly("mismatch_stiffness_minus20", g_true);
  for (int k = 0; k < 4; ++k) {
    for (int i = 0; i < 2; ++i) EXPECT_LE(std::abs(t.g[k][i] - g_true[i]), 1.5 * t.std[k][i]) << kTimesS[k];  // 0.9
  }
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(t.g[3][i], g_true[i], 0.045);  // 1.5 x the measured 0.028
}

}  // namespace
}  // namespace testing_support
}  // namespace birotor
