// The ground-contact judgement (estimator/ground_contact.h): the support
// force N = M a_z - (f1 + f2) low-passed against its hysteresis, the filter
// lengthened for a noisy accelerometer, one reading spike clamped, missing
// readings skipped, and Reset.
#include "estimator/ground_contact.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace birotor {
namespace {

TEST(GroundContactTest, SupportForceSaysGroundOrAir) {
  const BirotorParams p;  // M = 4.57624 kg
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
  // Hysteresis: 3 N (between off 1 N and on 4.5 N) keeps the state.
  for (int k = 300; k < 500; ++k) contact.Update(1000 * k, 9.81, p.TotalMass() * 9.81 - 3.0);
  EXPECT_FALSE(contact.supported());
}

// A noisy accelerometer lengthens the filter so that N's noise stays at a
// sixth of the hysteresis band: 1 m/s^2 (20x the reference) at 1 kHz gives
// tau = 0.001 (6 M / 3.5)^2 / 2 = 30.8 ms (M = 4.576 kg, band 4.5 - 1 N); the reference
// 0.05 m/s^2 keeps the option's 20 ms. (With 20 ms, N's sigma was 0.72 N and
// the contact chattered through lift-off in gauge_drift: README.)
TEST(GroundContactTest, NoisyAccelerometerLengthensTheFilter) {
  const BirotorParams p;
  EkfOptions options;
  EXPECT_DOUBLE_EQ(GroundContact(p, options).TimeConstantS(0.001), options.ground_contact_filter_s);
  options.accel_noise_m_s2 = 1.0;
  GroundContact contact(p, options);
  const double band_n = options.ground_contact_on_n - options.ground_contact_off_n;
  const double ratio = 6.0 * p.TotalMass() / band_n;
  EXPECT_NEAR(contact.TimeConstantS(0.001), 0.0005 * ratio * ratio, 1e-12);
  EXPECT_NEAR(contact.TimeConstantS(0.001), 0.0308, 0.0005);
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

// One absurd reading (1e6 m/s^2) in flight moves the filtered N by at most
// alpha M g (the clamp): with tau = 20 ms and dt = 1 ms, alpha = 1 - e^-0.05
// = 0.0488, so 0.0488 * 44.9 N = 2.19 N, below the 4.5 N that puts the
// vehicle on the ground. NaN readings (a missing accelerometer) are skipped.
TEST(GroundContactTest, ASpikeOrAMissingReadingCannotLandAFlyingVehicle) {
  const BirotorParams p;
  GroundContact contact(p, EkfOptions());
  const double weight_n = p.TotalMass() * p.gravity_m_s2;
  for (int k = 0; k < 100; ++k) contact.Update(1000 * k, p.gravity_m_s2, weight_n);
  EXPECT_FALSE(contact.supported());
  EXPECT_NEAR(contact.support_force_n(), 0.0, 1e-9);
  contact.Update(100000, 1e6, weight_n);
  EXPECT_NEAR(contact.support_force_n(), (1.0 - std::exp(-0.05)) * weight_n, 1e-9);
  EXPECT_FALSE(contact.supported());
  const double before = contact.support_force_n();
  contact.Update(101000, std::numeric_limits<double>::quiet_NaN(), weight_n);
  contact.Update(102000, p.gravity_m_s2, std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(contact.support_force_n(), before);
  EXPECT_FALSE(contact.supported());
}

// Reset forgets the filtered force: the next sample starts it afresh.
TEST(GroundContactTest, ResetStartsFromTheNextSample) {
  const BirotorParams p;
  GroundContact contact(p, EkfOptions());
  for (int k = 0; k < 100; ++k) contact.Update(1000 * k, 9.81, 0.0);
  ASSERT_TRUE(contact.supported());
  contact.Reset();
  EXPECT_FALSE(contact.supported());
  EXPECT_EQ(contact.support_force_n(), 0.0);
  contact.Update(200000, 9.81, p.TotalMass() * 9.81 - 10.0);  // N = 10 N at once, no filter lag
  EXPECT_NEAR(contact.support_force_n(), 10.0, 1e-9);
  EXPECT_TRUE(contact.supported());
}

}  // namespace
}  // namespace birotor
