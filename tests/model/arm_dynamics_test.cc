// The reduced arm models against the full model of model/birotor_dynamics.h.
#include "model/arm_dynamics.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <random>

#include "model/plant.h"

namespace birotor {
namespace {

TEST(FreeArmDerivativeTest, MatchesFullModelAtAnyPoseAndVelocity) {
  const BirotorParams p;
  Coords<double> q, v;
  q << 0.3, -0.2, 0.25, -0.004, 0.003;  // phi and position arbitrary
  v << 0.7, -0.4, 0.6, 0.05, -0.08;     // body velocity arbitrary
  const double f1 = 21.0, f2 = 24.5;
  const Coords<double> full = GeneralizedAcceleration<double>(p, q, v, f1, f2);
  FreeArmState<double> x;
  x(kFreePhiDot) = v(kPhi);
  x(kFreeB1) = q(kB1);
  x(kFreeB2) = q(kB2);
  x(kFreeB1Dot) = v(kB1);
  x(kFreeB2Dot) = v(kB2);
  Eigen::Vector2d specific_force;
  const FreeArmState<double> x_dot =
      FreeArmDerivative<double>(p, p.arm_stiffness_n_m_rad, p.arm_damping_n_m_s_rad, x, f1, f2, &specific_force);
  EXPECT_NEAR(x_dot(kFreePhiDot), full(kPhi), 1e-9 * std::abs(full(kPhi)) + 1e-9);
  EXPECT_NEAR(x_dot(kFreeB1Dot), full(kB1), 1e-9 * std::abs(full(kB1)));
  EXPECT_NEAR(x_dot(kFreeB2Dot), full(kB2), 1e-9 * std::abs(full(kB2)));
  EXPECT_EQ(x_dot(kFreeB1), v(kB1));
  // Specific force in body axes: R(phi)^T (p_ddot + [0, g]).
  const double c = std::cos(q(kPhi)), s = std::sin(q(kPhi));
  const double ax = full(kX), az = full(kZ) + p.gravity_m_s2;
  EXPECT_NEAR(specific_force(0), c * ax + s * az, 1e-9);
  EXPECT_NEAR(specific_force(1), -s * ax + c * az, 1e-9);
}

// With x, z, phi held (their rows carry the clamp's reaction) the b rows of
// M q_ddot = tau - C - G read M_bb b_ddot = (tau - C - G)_b: the full model's
// terms at the clamped pose give the closed form's acceleration, for one arm
// and for both (SupportedArmAcceleration, the EKF's model on the ground).
TEST(ClampedArmAccelerationTest, MatchesTheFullModelsArmRows) {
  const BirotorParams p;
  Coords<double> q = Coords<double>::Zero(), v = Coords<double>::Zero();
  q(kB1) = -0.002;
  q(kB2) = 0.0015;
  v(kB1) = 0.03;
  v(kB2) = -0.02;
  const double forces_n[2] = {19.4, 23.8};
  const DynamicsTerms<double> t = ComputeDynamicsTerms<double>(p, q, v, forces_n[0], forces_n[1]);
  for (int arm = 0; arm < 2; ++arm) {
    const int b = arm == 0 ? kB1 : kB2;
    const double expected = (t.generalized_thrust(b) - t.coriolis(b) - t.gravity_spring(b)) / t.mass(b, b);
    const double acc = ClampedArmAcceleration<double>(p, arm, p.arm_stiffness_n_m_rad, p.arm_damping_n_m_s_rad, q(b),
                                                      v(b), forces_n[arm]);
    EXPECT_NEAR(acc, expected, 1e-9 * std::abs(expected));
    const Eigen::Vector2d supported =
        SupportedArmAcceleration<double>(p, q(kB1), q(kB2), v(kB1), v(kB2), forces_n[0], forces_n[1]);
    EXPECT_NEAR(supported(arm), expected, 1e-9 * std::abs(expected));
  }
}

// Free body in uniform gravity: the phi, b1, b2 accelerations do not depend on
// x, z, phi, x_dot, z_dot (thesis ch. 4: these are the unobservable states),
// so the reduced model equals the full one at any pose and body velocity
// (rounding only).
TEST(FreeArmDerivativeTest, GravityCancelsInTheRelativeMotion) {
  const BirotorParams p;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    Coords<double> q, v;
    q << 10.0 * u(rng), 10.0 * u(rng), 1.5 * u(rng), 0.01 * u(rng), 0.01 * u(rng);
    v << 5.0 * u(rng), 5.0 * u(rng), 2.0 * u(rng), 0.1 * u(rng), 0.1 * u(rng);
    const double f1 = 22.0 + 10.0 * u(rng), f2 = 22.0 + 10.0 * u(rng);
    const Coords<double> full = GeneralizedAcceleration<double>(p, q, v, f1, f2);
    FreeArmState<double> x;
    x << v(kPhi), q(kB1), q(kB2), v(kB1), v(kB2);
    const FreeArmState<double> reduced =
        FreeArmDerivative<double>(p, p.arm_stiffness_n_m_rad, p.arm_damping_n_m_s_rad, x, f1, f2);
    const double scale = 1.0 + full.cwiseAbs().maxCoeff();
    EXPECT_NEAR(reduced(kFreePhiDot), full(kPhi), 1e-12 * scale);
    EXPECT_NEAR(reduced(kFreeB1Dot), full(kB1), 1e-12 * scale);
    EXPECT_NEAR(reduced(kFreeB2Dot), full(kB2), 1e-12 * scale);
  }
}

TEST(FreeArmDerivativeTest, JetDerivativeInStiffnessMatchesFiniteDifference) {
  using Jet = ceres::Jet<double, 1>;
  const BirotorParams p;
  FreeArmState<double> x;
  x << 0.2, -0.002, 0.0025, 0.01, -0.02;
  const FreeArmState<Jet> xj = x.cast<Jet>();
  const Jet k(p.arm_stiffness_n_m_rad, 0);
  const FreeArmState<Jet> dj = FreeArmDerivative<Jet>(p, k, Jet(p.arm_damping_n_m_s_rad), xj, Jet(22.0), Jet(23.0));
  const double h = 1e-3;
  const FreeArmState<double> plus =
      FreeArmDerivative<double>(p, p.arm_stiffness_n_m_rad + h, p.arm_damping_n_m_s_rad, x, 22.0, 23.0);
  const FreeArmState<double> minus =
      FreeArmDerivative<double>(p, p.arm_stiffness_n_m_rad - h, p.arm_damping_n_m_s_rad, x, 22.0, 23.0);
  for (int i = 0; i < kFreeArmStateSize; ++i) {
    const double fd = (plus(i) - minus(i)) / (2 * h);
    EXPECT_NEAR(dj(i).v(0), fd, 1e-6 * std::abs(fd) + 1e-9) << i;
  }
}

TEST(MotorStepTest, ExactFirstOrderResponse) {
  // After one time constant a step has covered 1 - 1/e of the way.
  EXPECT_NEAR(MotorStep(300.0, 1100.0, 0.035, 0.035), 1100.0 - 800.0 / std::exp(1.0), 1e-9);
}

}  // namespace
}  // namespace birotor
