// The rotor speed lag (model/plant.h MotorLagRate, the one copy) and the
// clamped bench plant (model/bench_dynamics.h).
#include "model/plant.h"

#include <gtest/gtest.h>

#include "model/bench_dynamics.h"

namespace birotor {
namespace {

// omega_dot = (clamp(omega_cmd) - omega) / tau_m with the reference
// vehicle's tau_m = 0.035 s and omega_max (model/birotor_params.h).
TEST(MotorLagRateTest, FirstOrderLagWithTheCommandClamped) {
  const BirotorParams p;
  EXPECT_DOUBLE_EQ(MotorLagRate(p, 300.0, 1100.0), 800.0 / 0.035);
  EXPECT_DOUBLE_EQ(MotorLagRate(p, 300.0, -50.0), -300.0 / 0.035);  // a negative command is 0
  EXPECT_DOUBLE_EQ(MotorLagRate(p, 300.0, 10.0 * p.omega_max_rad_s), (p.omega_max_rad_s - 300.0) / 0.035);
}

// The exact step MotorStep is the solution of the same lag: its slope at
// dt -> 0 is MotorLagRate (forward difference over 1 ns: relative error
// dt / (2 tau_m) = 1.4e-8).
TEST(MotorLagRateTest, IsTheSlopeOfTheExactStep) {
  const BirotorParams p;
  const double dt_s = 1e-9;
  const double slope = (MotorStep(300.0, 1100.0, p.motor_time_constant_s, dt_s) - 300.0) / dt_s;
  EXPECT_NEAR(slope, MotorLagRate(p, 300.0, 1100.0), 1e-6 * MotorLagRate(p, 300.0, 1100.0));
}

// On the bench the body is held: only the arms and the rotors move, and
// the rotors follow the same lag as in flight.
TEST(ClampedBodyDerivativeTest, BodyHeldRotorsLag) {
  const BirotorParams p;
  PlantState x = PlantState::Zero();
  x(kPlantOmega1) = 500.0;
  x(kPlantOmega2) = 600.0;
  PlantInput u;
  u.omega_cmd_rad_s[0] = 700.0;
  u.omega_cmd_rad_s[1] = 400.0;
  const PlantState x_dot = ClampedBodyDerivative(p, x, u);
  EXPECT_EQ(x_dot(kPlantOmega1), MotorLagRate(p, 500.0, 700.0));
  EXPECT_EQ(x_dot(kPlantOmega2), MotorLagRate(p, 600.0, 400.0));
  EXPECT_EQ(PlantDerivative(p, x, u)(kPlantOmega1), x_dot(kPlantOmega1));
  for (const int held : {kX, kZ, kPhi}) {
    EXPECT_EQ(x_dot(kPlantQ + held), 0.0);
    EXPECT_EQ(x_dot(kPlantV + held), 0.0);
  }
  // Arm 1 from rest under the thrust of 500 rad/s: the clamped-arm row of
  // thesis eq. 3.10 (model/arm_dynamics.h).
  EXPECT_EQ(x_dot(kPlantV + kB1), ClampedArmAcceleration<double>(p, 0, p.arm_stiffness_n_m_rad, p.arm_damping_n_m_s_rad,
                                                                 0.0, 0.0, RotorThrust(p, 500.0, 1.0)));
}

}  // namespace
}  // namespace birotor
