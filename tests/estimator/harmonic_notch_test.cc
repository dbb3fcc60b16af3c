// Tests of the tracked rotor-harmonic notches (estimator/harmonic_notch.h) and
// of the ground-contact judgement (estimator/ground_contact.h).
#include "estimator/harmonic_notch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "estimator/ground_contact.h"

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

TEST(GroundContactTest, SupportForceSaysGroundOrAir) {
  const VehicleParams p;  // M = 4.57624 kg
  GroundContact contact(p, EkfOptions());
  // At rest, motors stopped: N = M g = 44.9 N.
  for (int k = 0; k < 100; ++k) contact.Update(1000 * k, 9.81, 0.0);
  EXPECT_TRUE(contact.supported());
  EXPECT_NEAR(contact.support_force_n(), p.TotalMass() * 9.81, 1e-9);
  // In the air the rotors carry the vehicle: M a_z = f1 + f2, N = 0.
  for (int k = 100; k < 300; ++k) contact.Update(1000 * k, 9.81, p.TotalMass() * 9.81);
  EXPECT_FALSE(contact.supported());
  // First-order decay from M g with tau = 20 ms over 200 ms: M g e^-10.
  EXPECT_NEAR(contact.support_force_n(), p.TotalMass() * 9.81 * std::exp(-10.0), 1e-9);
  // Hysteresis: 3 N (between off 2 N and on 4.5 N) keeps the state.
  for (int k = 300; k < 500; ++k) contact.Update(1000 * k, 9.81, p.TotalMass() * 9.81 - 3.0);
  EXPECT_FALSE(contact.supported());
}

// A noisy accelerometer lengthens the filter so that N's noise stays at a
// sixth of the hysteresis band: 1 m/s^2 (20x the reference) at 1 kHz gives
// tau = 0.001 (6 M / 2.5)^2 / 2 = 60 ms (M = 4.576 kg); the reference
// 0.05 m/s^2 keeps the option's 20 ms. (With 20 ms, N's sigma was 0.72 N and
// the contact chattered through lift-off in gauge_drift: README.)
TEST(GroundContactTest, NoisyAccelerometerLengthensTheFilter) {
  const VehicleParams p;
  EkfOptions options;
  EXPECT_DOUBLE_EQ(GroundContact(p, options).TimeConstantS(0.001), options.ground_contact_filter_s);
  options.accel_noise_m_s2 = 1.0;
  GroundContact contact(p, options);
  const double band_n = options.ground_contact_on_n - options.ground_contact_off_n;
  const double ratio = 6.0 * p.TotalMass() / band_n;
  EXPECT_NEAR(contact.TimeConstantS(0.001), 0.0005 * ratio * ratio, 1e-12);
  EXPECT_NEAR(contact.TimeConstantS(0.001), 0.060, 0.001);
  // 20 s of hover with that noise: the filtered N scatters by band / 6.
  std::mt19937 rng(29);
  std::normal_distribution<double> noise(0.0, 1.0);
  double sum = 0, sum_sq = 0;
  int n = 0;
  for (int k = 0; k < 20000; ++k) {
    contact.Update(1000 * k, 9.81 + noise(rng), p.TotalMass() * 9.81);
    if (k < 1000) continue;  // settle
    sum += contact.support_force_n();
    sum_sq += contact.support_force_n() * contact.support_force_n();
    ++n;
  }
  const double std_n = std::sqrt(sum_sq / n - (sum / n) * (sum / n));
  EXPECT_NEAR(std_n, band_n / 6.0, 0.1 * band_n / 6.0);
  EXPECT_FALSE(contact.supported());
}

}  // namespace
}  // namespace birotor
