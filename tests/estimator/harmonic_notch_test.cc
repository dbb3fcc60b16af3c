// Tests of the tracked rotor-harmonic notches (estimator/harmonic_notch.h).
#include "estimator/harmonic_notch.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace birotor {
namespace {

// Amplitude of x (mean removed) at angular frequency w over the samples.
double Amplitude(const std::vector<double>& x, double dt_s, double w) {
  double mean = 0;
  for (double v : x) mean += v / static_cast<double>(x.size());
  double c = 0, s = 0;
  for (size_t k = 0; k < x.size(); ++k) {
    c += (x[k] - mean) * std::cos(w * k * dt_s);
    s += (x[k] - mean) * std::sin(w * k * dt_s);
  }
  return 2.0 * std::hypot(c, s) / static_cast<double>(x.size());
}

TEST(HarmonicNotchTest, RemovesBothHarmonicsAndPassesTheArmSignal) {
  HarmonicNotchOptions options;  // 4 Hz wide
  HarmonicNotch notch(options);
  const double dt_s = 1e-3, omega[2] = {698.55, 720.0};  // hover speed, reference-vehicle.md
  const double w_slow = 2.0 * M_PI * 2.0;                // a 2 Hz manoeuvre
  std::vector<double> out[2], slow;
  for (int k = 0; k < 4000; ++k) {
    const double t = k * dt_s;
    StrainSample s;
    for (int i = 0; i < 2; ++i) {
      // gauge_vibration.yaml amplitudes: 3e-5 at 1x, 2e-5 at 2x.
      s.deflection_rad[i] = -0.0018664 + 1e-4 * std::sin(w_slow * t) + 3e-5 * std::sin(omega[i] * t) +
                            2e-5 * std::sin(2 * omega[i] * t + 0.7);
    }
    notch.Apply(k == 0 ? 0.0 : dt_s, omega, &s);
    if (k >= 2000) {  // after the notches settled (time constant 1 / (pi 4 Hz) = 80 ms)
      for (int i = 0; i < 2; ++i) out[i].push_back(s.deflection_rad[i]);
    }
  }
  for (int i = 0; i < 2; ++i) {
    EXPECT_LT(Amplitude(out[i], dt_s, omega[i]), 0.05 * 3e-5) << i;
    EXPECT_LT(Amplitude(out[i], dt_s, 2 * omega[i]), 0.05 * 2e-5) << i;
    // 2 Hz passes with unit gain (to 0.5 %), DC exactly.
    EXPECT_NEAR(Amplitude(out[i], dt_s, w_slow), 1e-4, 0.5e-6) << i;
    double mean = 0;
    for (double v : out[i]) mean += v / out[i].size();
    EXPECT_NEAR(mean, -0.0018664, 2e-7);
  }
}

TEST(HarmonicNotchTest, PassesWhenTheRotorsAreSlowOrOff) {
  HarmonicNotch notch(HarmonicNotchOptions{});
  const double omega[2] = {50.0, 0.0};  // below min_speed_rad_s = 100
  for (int k = 0; k < 100; ++k) {
    StrainSample s;
    s.deflection_rad[0] = 2.69e-4 + 1e-5 * std::sin(0.05 * k);
    s.deflection_rad[1] = -2.69e-4;
    const StrainSample in = s;
    notch.Apply(1e-3, omega, &s);
    EXPECT_EQ(s.deflection_rad[0], in.deflection_rad[0]);
    EXPECT_EQ(s.deflection_rad[1], in.deflection_rad[1]);
  }
  HarmonicNotchOptions off;
  off.enabled = false;
  HarmonicNotch disabled(off);
  StrainSample s;
  s.deflection_rad[0] = 1.0;
  const double hover[2] = {700.0, 700.0};
  disabled.Apply(1e-3, hover, &s);
  EXPECT_EQ(s.deflection_rad[0], 1.0);
}

// The N-arm notch (MultiArmPipeline's): three arms at the trirotor's hover
// speeds (config/vehicles/trirotor.yaml: 772.7, 557.9, 557.9 rad/s), each
// gauge with its own rotor's 1x and 2x pickup; every arm's harmonics are
// removed and a 2 Hz manoeuvre passes, at the N-arm width of 2 Hz.
TEST(HarmonicNotchTest, RemovesEachArmsHarmonicsOnThreeArms) {
  HarmonicNotchOptions options;
  options.bandwidth_hz = options.multi_arm_bandwidth_hz;
  HarmonicNotch notch(options, 3);
  ASSERT_EQ(notch.arm_count(), 3);
  const double dt_s = 1e-3, w_slow = 2.0 * M_PI * 2.0;
  const std::array<double, kMaxArms> omega = {772.7, 557.9, 580.0};  // arm 3 off arm 2's speed
  std::vector<double> out[3];
  for (int k = 0; k < 6000; ++k) {
    const double t = k * dt_s;
    MultiArmStrainSample s;
    s.n_arms = 3;
    for (size_t i = 0; i < 3; ++i) {
      s.deflection_rad[i] = -0.0026 + 1e-4 * std::sin(w_slow * t) + 3e-5 * std::sin(omega[i] * t) +
                            2e-5 * std::sin(2 * omega[i] * t + 0.7 * static_cast<double>(i));
    }
    notch.Apply(k == 0 ? 0.0 : dt_s, omega, &s);
    if (k >= 4000) {  // settled: time constant 1 / (pi 2 Hz) = 160 ms
      for (size_t i = 0; i < 3; ++i) out[i].push_back(s.deflection_rad[i]);
    }
  }
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_LT(Amplitude(out[i], dt_s, omega[i]), 0.05 * 3e-5) << i;
    EXPECT_LT(Amplitude(out[i], dt_s, 2 * omega[i]), 0.05 * 2e-5) << i;
    EXPECT_NEAR(Amplitude(out[i], dt_s, w_slow), 1e-4, 0.5e-6) << i;
  }
  // Arm 3's own notch, not arm 2's: arm 2's 1x passes arm 3 almost unchanged
  // (22 rad/s = 3.5 Hz away from a 2 Hz wide notch).
  EXPECT_GT(Amplitude(out[2], dt_s, omega[1]), 0.0);
}

// A NaN deflection (no gauge reading of that arm) passes, the other arms are
// filtered as before, and the arm's notches restart at its next reading
// (which passes unchanged).
TEST(HarmonicNotchTest, PassesAMissingReadingAndRestartsThatArm) {
  HarmonicNotch notch(HarmonicNotchOptions{}, 3);
  const std::array<double, kMaxArms> omega = {700.0, 700.0, 700.0};
  MultiArmStrainSample s;
  s.n_arms = 3;
  for (int k = 0; k < 50; ++k) {
    for (size_t i = 0; i < 3; ++i) s.deflection_rad[i] = 1e-4 * std::sin(0.7 * k);
    notch.Apply(1e-3, omega, &s);
  }
  s.deflection_rad = {2e-4, std::nan(""), 2e-4};
  notch.Apply(1e-3, omega, &s);
  EXPECT_TRUE(std::isnan(s.deflection_rad[1]));
  EXPECT_TRUE(std::isfinite(s.deflection_rad[0]));
  s.deflection_rad = {2e-4, 3e-4, 2e-4};
  notch.Apply(1e-3, omega, &s);
  EXPECT_EQ(s.deflection_rad[1], 3e-4);
  EXPECT_TRUE(std::isfinite(s.deflection_rad[0]));
}

// The birotor's notch is bit-for-bit the one before the N-arm
// generalisation: the reference below is that code (one DF-I section per arm
// and harmonic, as in 09d04fc), fed the same tracked-speed sweep and
// restarts (a slow rotor, a long interval).
TEST(HarmonicNotchTest, BirotorOutputIsBitForBitTheTwoArmReference) {
  const HarmonicNotchOptions options;
  HarmonicNotch notch(options);
  double mem[2][2][4] = {};  // x1 x2 y1 y2 per arm and harmonic
  bool primed[2][2] = {};
  for (int k = 0; k < 3000; ++k) {
    const double dt_s = k == 1500 ? 0.02 : 1e-3;  // one interval beyond max_dt_s
    const double omega[2] = {600.0 + 0.1 * k, k < 200 ? 50.0 : 720.0 - 0.05 * k};
    StrainSample s;
    for (int i = 0; i < 2; ++i) s.deflection_rad[i] = 1e-3 * std::sin(0.3 * k + i) + 3e-5 * std::sin(1.1 * k);
    double expected[2];
    const bool dt_ok = dt_s > 0 && dt_s <= options.max_dt_s;
    const double r = std::exp(-M_PI * options.bandwidth_hz * dt_s);
    for (int arm = 0; arm < 2; ++arm) {
      double x = s.deflection_rad[arm];
      for (int h = 0; h < 2; ++h) {
        double* m = mem[arm][h];
        const double w0 = (h + 1) * omega[arm] * dt_s;
        double y = x;
        if (dt_ok && primed[arm][h] && omega[arm] >= options.min_speed_rad_s && w0 <= 0.9 * M_PI) {
          const double c = std::cos(w0);
          const double gain = (1.0 - 2.0 * r * c + r * r) / (2.0 - 2.0 * c);
          y = gain * (x - 2.0 * c * m[0] + m[1]) + 2.0 * r * c * m[2] - r * r * m[3];
          m[1] = m[0];
          m[3] = m[2];
          m[0] = x;
          m[2] = y;
        } else {
          m[0] = m[1] = m[2] = m[3] = x;
          primed[arm][h] = true;
        }
        x = y;
      }
      expected[arm] = x;
    }
    notch.Apply(dt_s, omega, &s);
    ASSERT_EQ(s.deflection_rad[0], expected[0]) << k;
    ASSERT_EQ(s.deflection_rad[1], expected[1]) << k;
  }
}

}  // namespace
}  // namespace birotor
