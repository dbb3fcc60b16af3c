// The cascaded law against its equations (position_attitude_law.h) on the
// reference vehicle (shared/spec/reference-vehicle.md), and the inverse
// thrust map against f = mu c_T omega^2.
#include "controller/position_attitude_law.h"

#include <gtest/gtest.h>

#include <cmath>

#include "model/equilibrium.h"

namespace birotor {
namespace {

double HoverForce(const BirotorParams& p) {
  const Equilibrium e = SolveHoverEquilibrium(p);
  return 0.5 * (e.force_n[0] + e.force_n[1]);
}

TEST(PositionAttitudeLawTest, AtTheReferenceEachRotorMakesTheHoverForce) {
  const BirotorParams vehicle;
  PositionAttitudeLaw law(vehicle, ControllerParams(), HoverForce(vehicle));
  const RotorForces f = law.Update(BodyState(), ReferencePoint());
  EXPECT_DOUBLE_EQ(f.force_n[0], HoverForce(vehicle));
  EXPECT_DOUBLE_EQ(f.force_n[1], HoverForce(vehicle));
  EXPECT_EQ(f.accel_des_m_s2, Eigen::Vector2d::Zero());
}

TEST(PositionAttitudeLawTest, TiltErrorGivesTheTorqueOfEquation312) {
  const BirotorParams vehicle;
  const ControllerParams gains;
  PositionAttitudeLaw law(vehicle, gains, HoverForce(vehicle));
  BodyState state;
  state.phi_rad = 0.01;
  const RotorForces f = law.Update(state, ReferencePoint());
  // e_phi = -0.01, one step of the integral: alpha = Kp e + Ki dt e.
  const double dt = 1.0 / gains.rate_hz;
  const double alpha = gains.attitude_kp_1_s2 * -0.01 + gains.attitude_ki_1_s3 * dt * -0.01;
  const double L = vehicle.arm_length_m;
  const double inertia = vehicle.body_inertia_kg_m2 + 2.0 * vehicle.tip_mass_kg * L * L;
  EXPECT_NEAR(f.force_n[1] - f.force_n[0], inertia * alpha / L, 1e-12);
  EXPECT_NEAR(f.force_n[0] + f.force_n[1], 2.0 * HoverForce(vehicle) / std::cos(0.01), 1e-12);
}

TEST(PositionAttitudeLawTest, ResetClearsTheIntegrators) {
  const BirotorParams vehicle;
  PositionAttitudeLaw law(vehicle, ControllerParams(), HoverForce(vehicle));
  BodyState low;
  low.position_m.y() = -0.1;
  const RotorForces first = law.Update(low, ReferencePoint());
  law.Update(low, ReferencePoint());
  law.Reset();
  const RotorForces after_reset = law.Update(low, ReferencePoint());
  EXPECT_DOUBLE_EQ(after_reset.force_n[0], first.force_n[0]);
}

TEST(RotorSpeedForThrustTest, InvertsTheThrustMapAndClips) {
  const BirotorParams vehicle;
  bool saturated = true;
  const double omega = RotorSpeedForThrust(vehicle, 20.0, 0.75, &saturated);
  EXPECT_NEAR(0.75 * vehicle.thrust_coeff_n_s2_rad2 * omega * omega, 20.0, 1e-9);
  EXPECT_FALSE(saturated);
  EXPECT_EQ(RotorSpeedForThrust(vehicle, 1e6, 1.0, &saturated), vehicle.omega_max_rad_s);
  EXPECT_TRUE(saturated);
  EXPECT_EQ(RotorSpeedForThrust(vehicle, -3.0, 1.0, &saturated), 0.0);
  EXPECT_TRUE(saturated);
}

}  // namespace
}  // namespace birotor
