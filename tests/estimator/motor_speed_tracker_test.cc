// The baselines' rotor speeds (estimator/motor_speed_tracker.h): telemetry
// while it is recent, else the first-order motor model over the commands
// (model/plant.h MotorStep: omega = c + (omega0 - c) e^(-dt / tau_m)).
#include "estimator/motor_speed_tracker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace birotor {
namespace {

MotorSample Motor(int64_t utime, double command_rad_s, double measured_rad_s) {
  MotorSample m;
  m.utime = utime;
  m.omega_cmd_rad_s[0] = m.omega_cmd_rad_s[1] = command_rad_s;
  m.omega_meas_rad_s[0] = m.omega_meas_rad_s[1] = measured_rad_s;
  return m;
}

TEST(MotorSpeedTrackerTest, UsesRecentTelemetryThenTheMotorModel) {
  const BirotorParams p;
  MotorSpeedTracker tracker(p, 0.05);
  EXPECT_FALSE(tracker.has_motor());
  EXPECT_EQ(tracker.ThrustScale(0, 2.0), 1.0);  // without motor input
  tracker.AddMotor(Motor(0, 700.0, 650.0));
  tracker.Advance(10000);
  EXPECT_TRUE(tracker.from_telemetry(0));
  EXPECT_EQ(tracker.omega_rad_s(0), 650.0);
  // Telemetry older than 50 ms: the model, started at the telemetry and
  // driven by the 700 rad/s command for 60 ms.
  tracker.Advance(60000);
  EXPECT_FALSE(tracker.from_telemetry(1));
  const double expected = 700.0 + (650.0 - 700.0) * std::exp(-0.06 / p.motor_time_constant_s);
  EXPECT_NEAR(tracker.omega_rad_s(1), expected, 1e-9);
  // Thrust scale: f / (c_T omega^2).
  const double nominal = p.thrust_coeff_n_s2_rad2 * expected * expected;
  EXPECT_NEAR(tracker.ThrustScale(1, 0.9 * nominal), 0.9, 1e-12);
}

TEST(MotorSpeedTrackerTest, WithoutTelemetryTheModelStartsAtTheCommand) {
  const BirotorParams p;
  MotorSpeedTracker tracker(p);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  tracker.AddMotor(Motor(0, 600.0, nan));
  tracker.Advance(0);
  EXPECT_FALSE(tracker.from_telemetry(0));
  EXPECT_NEAR(tracker.omega_rad_s(0), 600.0, 1e-9);
  tracker.AddMotor(Motor(1000, 800.0, nan));
  tracker.Advance(21000);  // 20 ms toward 800
  EXPECT_NEAR(tracker.omega_rad_s(0), 800.0 - 200.0 * std::exp(-0.02 / p.motor_time_constant_s), 1e-9);
  tracker.Reset();
  EXPECT_FALSE(tracker.has_motor());
  EXPECT_EQ(tracker.omega_rad_s(0), 0.0);
}

}  // namespace
}  // namespace birotor
