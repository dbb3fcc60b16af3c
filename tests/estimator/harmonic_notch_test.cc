// Tests of the tracked rotor-harmonic notches (estimator/harmonic_notch.h).
#include "estimator/harmonic_notch.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace birotor
