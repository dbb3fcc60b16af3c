// The MPC's prediction model against the reference vehicle's hover values and
// the rigid-body equations, and its linearisation against the step it came from.
#include "controller/mpc_model.h"

#include <gtest/gtest.h>

#include "controller/position_attitude_law.h"

namespace birotor {
namespace {

MpcState Hover(const MpcPredictionModel& model) {
  MpcState s = MpcState::Zero();
  s(kMpcOmega1) = s(kMpcOmega2) = RotorSpeedForThrust(model.vehicle(), model.hover_force_n(), 1.0);
  return s;
}

TEST(MpcModelTest, HoverIsAFixedPoint) {
  const MpcPredictionModel model{BirotorParams()};
  const MpcState s = Hover(model);
  // reference-vehicle.md: omega = 698.55 rad/s at hover (f = 22.4465 N).
  EXPECT_NEAR(s(kMpcOmega1), 698.55, 0.01);
  const MpcState s_dot = model.Derivative(s, s.tail<2>(), MpcModelContext());
  EXPECT_LT(s_dot.norm(), 1e-9);
}

TEST(MpcModelTest, RigidBodyAccelerations) {
  const BirotorParams p;
  const MpcPredictionModel model(p);
  MpcState s = Hover(model);
  // One newton more on rotor 2 than on rotor 1 (rotor 1 1/2 N less, rotor 2 1/2 N more):
  // phi_ddot = L (f2 - f1) / (J + 2 m_p L^2) (thesis eq. 3.12 with rigid arms) = 2.9064 rad/s^2.
  const double f = model.hover_force_n();
  s(kMpcOmega1) = RotorSpeedForThrust(p, f - 0.5, 1.0);
  s(kMpcOmega2) = RotorSpeedForThrust(p, f + 0.5, 1.0);
  MpcState s_dot = model.Derivative(s, s.tail<2>(), MpcModelContext());
  const double inertia = p.body_inertia_kg_m2 + 2.0 * p.tip_mass_kg * p.arm_length_m * p.arm_length_m;
  EXPECT_NEAR(s_dot(kMpcPhiDot), p.arm_length_m * 1.0 / inertia, 1e-3);
  // Two newtons more in total: z_ddot = 2 / (m + 2 m_p) = 0.4364 m/s^2.
  s(kMpcOmega1) = s(kMpcOmega2) = RotorSpeedForThrust(p, f + 1.0, 1.0);
  s_dot = model.Derivative(s, s.tail<2>(), MpcModelContext());
  EXPECT_NEAR(s_dot(kMpcZDot), 2.0 / p.TotalMass(), 1e-4);
  // The thrust scale enters the thrust: rotor 2 at 0.6 loses 0.4 f of its thrust.
  s = Hover(model);
  MpcModelContext weak;
  weak.thrust_scale << 1.0, 0.6;
  s_dot = model.Derivative(s, s.tail<2>(), weak);
  EXPECT_NEAR(s_dot(kMpcZDot), -0.4 * f / p.TotalMass(), 1e-4);
  EXPECT_NEAR(s_dot(kMpcPhiDot), -p.arm_length_m * 0.4 * f / inertia, 2e-3);
}

TEST(MpcModelTest, MotorLagMatchesTheExactStep) {
  const BirotorParams p;
  const MpcPredictionModel model(p);
  MpcState s = Hover(model);
  const Eigen::Vector2d command(900.0, 500.0);
  const MpcState next = model.Step(s, command, MpcModelContext(), 0.02);
  // omega+ = c + (omega - c) exp(-dt / tau_m) (model/plant.h MotorStep); RK4 at dt/tau = 0.57: 1e-3 relative.
  EXPECT_NEAR(next(kMpcOmega1), 900.0 + (s(kMpcOmega1) - 900.0) * std::exp(-0.02 / 0.035), 0.2);
  EXPECT_NEAR(next(kMpcOmega2), 500.0 + (s(kMpcOmega2) - 500.0) * std::exp(-0.02 / 0.035), 0.2);
}

TEST(MpcModelTest, LinearisationPredictsSmallDeviations) {
  const MpcPredictionModel model{BirotorParams()};
  MpcState s0 = Hover(model);
  s0(kMpcPhi) = 0.2;
  s0(kMpcXDot) = 0.5;
  const Eigen::Vector2d u0(720.0, 680.0);
  MpcModelContext context;
  context.thrust_scale << 0.9, 0.7;
  const MpcLinearStep lin = model.Linearize(s0, u0, context, 0.02);
  // Exact at the point.
  EXPECT_LT((lin.a * s0 + lin.b * u0 + lin.c - model.Step(s0, u0, context, 0.02)).norm(), 1e-9);
  // Small deviations: second-order error only.
  MpcState ds = MpcState::Zero();
  ds << 0.01, -0.01, 0.01, 0.02, 0.0, 0.05, 3.0, -3.0;
  const Eigen::Vector2d du(5.0, -5.0);
  const MpcState linear = lin.a * (s0 + ds) + lin.b * (u0 + du) + lin.c;
  const MpcState exact = model.Step(s0 + ds, u0 + du, context, 0.02);
  EXPECT_LT((linear - exact).norm(), 2e-4);
}

}  // namespace
}  // namespace birotor
