// Tests of estimator/gauge_tare.h and gauge_calibration.h on synthetic
// samples: the tare rule, its estimate and sigma, and every refusal.
#include "estimator/gauge_tare.h"

#include <gtest/gtest.h>

#include <cmath>

#include "simulator/noise.h"

namespace birotor {
namespace {

// m_p g L / k of the reference vehicle [rad].
constexpr double kRest = 0.28812 * 9.81 * 0.25 / 2628.0;

// Drives a GaugeTare at 1 kHz strain, 500 Hz motor, 1 kHz IMU.
struct TareBench {
  TareBench() : tare(BirotorParams(), TareOptions()), noise(5, 9) {}
  // Feeds duration_s from utime; readings s b_rest + offset + noise.
  void Run(double duration_s, const double offset[2], double omega_cmd = 0.0, double gyro = 0.0,
           double noise_rad = 2e-5) {
    for (int k = 0; k < std::lround(duration_s * 1000); ++k, utime += 1000) {
      if (k % 2 == 0) {
        MotorSample m;
        m.utime = utime;
        m.omega_cmd_rad_s[0] = m.omega_cmd_rad_s[1] = omega_cmd;
        m.omega_meas_rad_s[0] = m.omega_meas_rad_s[1] = omega_cmd;
        tare.AddMotor(m);
      }
      ImuSample imu;
      imu.utime = utime;
      imu.gyro_y_rad_s = gyro;
      imu.accel_z_m_s2 = 9.81;
      tare.AddImu(imu);
      StrainSample s;
      s.utime = utime;
      s.deflection_rad[0] = kRest + offset[0] + noise.Normal(noise_rad);
      s.deflection_rad[1] = -kRest + offset[1] + noise.Normal(noise_rad);
      const TareEvent event = tare.AddStrain(s);
      if (event == TareEvent::kAccepted) ++accepted_events;
      if (event == TareEvent::kRefused) ++refused_events;
    }
  }
  GaugeTare tare;
  GaussianSource noise;
  int64_t utime = 1'000'000;
  int accepted_events = 0, refused_events = 0;
};

TEST(GaugeTareTest, RestDeflectionIsTheTipWeightOverTheStiffness) {
  const BirotorParams p;
  EXPECT_NEAR(StaticDeflectionRad(p, 0, 0.0), 2.6887e-4, 1e-8);  // arm 1 bends up under its weight
  EXPECT_NEAR(StaticDeflectionRad(p, 1, 0.0), -2.6887e-4, 1e-8);
  BirotorParams scaled;
  scaled.gauge_scale[0] = 1.03;
  EXPECT_NEAR(RestReadingRad(scaled, 0), 1.03 * 2.6887e-4, 1e-8);
}

TEST(GaugeTareTest, ThreeSecondsAtRestGiveTheOffsetToItsStandardError) {
  TareBench bench;
  const double offset[2] = {1.5e-5, -1.0e-5};  // gauges.md reference offsets
  bench.Run(3.0, offset);
  EXPECT_EQ(bench.accepted_events, 2);  // at 1 s, refined at 2 s (the 3 s mark is the last sample)
  EXPECT_EQ(bench.tare.counters().accepted, 2);
  // sigma = sqrt((2e-5)^2 / 2000 + (1e-6)^2) = 1.095e-6 rad after 2 s.
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(bench.tare.offset_std_rad()[i], 1.095e-6, 0.05e-6);
    EXPECT_NEAR(bench.tare.offset_rad()[i], offset[i], 3 * 0.45e-6);  // 3 sigma of the mean alone
  }
  // The rest ends after a tare: no refusal.
  bench.Run(0.5, offset, 300.0);
  EXPECT_EQ(bench.refused_events, 0);
}

TEST(GaugeTareTest, ARestTooShortBeforeTheMotorsStartIsRefused) {
  TareBench bench;
  const double offset[2] = {1.5e-5, -1.0e-5};
  bench.Run(0.5, offset);
  bench.Run(0.5, offset, 300.0);
  EXPECT_EQ(bench.refused_events, 1);
  EXPECT_EQ(bench.tare.counters().refused_motors_running, 1);
  EXPECT_EQ(bench.tare.counters().last_refusal, TareRefusal::kMotorsRunning);
  EXPECT_EQ(bench.tare.counters().accepted, 0);
  EXPECT_EQ(bench.tare.offset_rad()[0], 0.0);  // nothing applied
  EXPECT_STREQ(TareRefusalName(TareRefusal::kMotorsRunning), "motors_running");
}

TEST(GaugeTareTest, AMovingBodyIsRefused) {
  TareBench bench;
  const double offset[2] = {1.5e-5, -1.0e-5};
  bench.Run(0.5, offset);
  bench.Run(0.1, offset, 0.0, 0.2);  // gyro 0.2 rad/s > rest_gyro_rad_s 0.05
  EXPECT_EQ(bench.tare.counters().refused_body_moving, 1);
  EXPECT_EQ(bench.tare.counters().accepted, 0);
}

TEST(GaugeTareTest, AReadingOutsideThePhysicalRangeIsRefused) {
  TareBench bench;
  const double offset[2] = {8e-4, 0.0};  // > max_offset_rad 5e-4: a broken bridge, not an offset
  bench.Run(2.5, offset);
  EXPECT_EQ(bench.tare.counters().refused_out_of_range, 2);  // every window is refused
  EXPECT_EQ(bench.tare.counters().accepted, 0);
  EXPECT_EQ(bench.tare.offset_rad()[0], 0.0);
  EXPECT_EQ(bench.tare.counters().last_refusal, TareRefusal::kOutOfRange);
}

TEST(GaugeTareTest, NoTareWithoutMotorOrImuInput) {
  GaugeTare tare{BirotorParams(), TareOptions()};
  StrainSample s;
  s.deflection_rad[0] = kRest;
  s.deflection_rad[1] = -kRest;
  for (int k = 0; k < 3000; ++k) {
    s.utime = 1000 * k;
    EXPECT_EQ(tare.AddStrain(s), TareEvent::kNone);
  }
  TareRefusal why = TareRefusal::kNone;
  EXPECT_FALSE(tare.Resting(s.utime, &why));
  EXPECT_EQ(why, TareRefusal::kMotorsRunning);  // unknown motors count as running
}

TEST(GaugeCalibrationTest, AppliesScaleAndOffset) {
  BirotorParams p;
  p.gauge_scale[0] = 1.03;
  p.gauge_scale[1] = 0.98;
  p.gauge_offset_rad[0] = 1e-5;
  p.gauge_offset_rad[1] = -2e-5;
  const GaugeCalibration c = GaugeCalibration::FromVehicle(p);
  StrainSample raw;
  raw.deflection_rad[0] = 1.03 * -0.0018664 + 1e-5;
  raw.deflection_rad[1] = 0.98 * 0.0018664 - 2e-5;
  const StrainSample b = c.Apply(raw);
  EXPECT_NEAR(b.deflection_rad[0], -0.0018664, 1e-15);
  EXPECT_NEAR(b.deflection_rad[1], 0.0018664, 1e-15);
  EXPECT_EQ(c.offset_std_rad[0], 5e-5);  // gauge_offset_std_rad default
  EXPECT_STREQ(GaugeOffsetSourceName(c.source), "params");
}

}  // namespace
}  // namespace birotor
