// Hover, linearization and arm modes of the N-arm model: the birotor's
// equilibrium.h / linearization.h figures at N = 2, the Jet Jacobians against
// central differences, and the shipped trirotor's hover and modes.
#include "model/multi_arm_linearization.h"

#include <gtest/gtest.h>

#include <cmath>

#include "model/equilibrium.h"
#include "model/multi_arm_dynamics.h"
#include "tests/model/test_vehicles.h"

namespace birotor {
namespace {

using test_vehicles::Birotor;
using test_vehicles::Trirotor;

TEST(MultiArmHover, BirotorEqualsEquilibrium) {
  const BirotorParams params;
  const MultiArmHover hover = SolveMultiArmHover(Birotor(params));
  const Equilibrium eq = SolveHoverEquilibrium(params);
  ASSERT_TRUE(hover.converged);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(hover.force_n(i), eq.force_n[i], 1e-12);
    EXPECT_NEAR(hover.deflection_rad(i), eq.deflection_rad[i], 1e-15);
    // The rigid allocation is the thesis's g (m + 2 m_p) / 2 = 22.4465 N.
    EXPECT_NEAR(hover.allocation_force_n(i), params.HoverForceN(), 1e-12);
  }
  EXPECT_NEAR(hover.deflection_rad(0), -0.0018664, 1e-7);  // reference-vehicle.md
}

TEST(MultiArmLinearization, BirotorEqualsLinearization) {
  const BirotorParams params;
  const VehicleDescription vehicle = Birotor(params);
  const MultiArmLinearModel ours = LinearizeMultiArmAtHover(vehicle, SolveMultiArmHover(vehicle));
  const LinearModel reference = LinearizeAtHover(params);
  EXPECT_LT((ours.a - Eigen::MatrixXd(reference.a)).cwiseAbs().maxCoeff(), 1e-12 * reference.a.cwiseAbs().maxCoeff());
  EXPECT_LT((ours.b - Eigen::MatrixXd(reference.b)).cwiseAbs().maxCoeff(), 1e-12 * reference.b.cwiseAbs().maxCoeff());
  EXPECT_EQ(MultiArmStateNames(2), AugmentedStateNames());
  const Eigen::MatrixXd aug = AugmentMultiArmWithForces(ours);
  EXPECT_LT((aug - Eigen::MatrixXd(AugmentWithForces(reference))).cwiseAbs().maxCoeff(),
            1e-12 * reference.a.cwiseAbs().maxCoeff());
}

TEST(MultiArmLinearization, BirotorModesEqualLinearization) {
  const BirotorParams params;
  const VehicleDescription vehicle = Birotor(params);
  const std::vector<Mode> ours = OscillatoryModes(LinearizeMultiArmAtHover(vehicle, SolveMultiArmHover(vehicle)).a);
  const std::vector<Mode> reference = OscillatoryModes(LinearizeAtHover(params).a);
  ASSERT_EQ(ours.size(), 2u);
  ASSERT_EQ(reference.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(ours[i].frequency_hz, reference[i].frequency_hz, 1e-9);
    EXPECT_NEAR(ours[i].damping_ratio, reference[i].damping_ratio, 1e-9);
  }
  // reference-vehicle.md: 65.03 Hz (0.019) and 79.75 Hz (0.024).
  EXPECT_NEAR(ours[0].frequency_hz, 65.03, 0.01);
  EXPECT_NEAR(ours[1].frequency_hz, 79.75, 0.01);
}

TEST(MultiArmHover, TrirotorHoldsStill) {
  const VehicleDescription vehicle = Trirotor();
  const MultiArmHover hover = SolveMultiArmHover(vehicle);
  ASSERT_TRUE(hover.converged);
  // Rigid allocation, closed form: the F_x row gives f_2 = f_3 = f, the
  // torque row -L f_1 + 2 L f = m_p g L (cos 180 + 2 cos 45 deg) (the tip
  // weights' moment about the centre), F_z f_1 + sqrt(2) f = W: f = 14.3196 N,
  // f_1 = 27.4684 N: SolveHover's figures (docs/vehicle-description.md).
  const ArmDescription& arm = vehicle.arms[0];
  const double weight_n = vehicle.gravity_m_s2 * vehicle.TotalMass();
  const double tip_moment_n = arm.tip_mass_kg * vehicle.gravity_m_s2 * (std::sqrt(2.0) - 1.0);  // over L
  const double f_n = (weight_n + tip_moment_n) / (2.0 + std::sqrt(2.0));
  EXPECT_NEAR(hover.allocation_force_n(0), 2.0 * f_n - tip_moment_n, 1e-9);
  EXPECT_NEAR(hover.allocation_force_n(1), f_n, 1e-9);
  EXPECT_NEAR(hover.allocation_force_n(2), f_n, 1e-9);
  // The deflected equilibrium, printed by birotor-analyze --vehicle
  // config/vehicles/trirotor.yaml (docs/multi-arm-model.md): the arm
  // deflections turn the thrusts, so rotors 2 and 3 part by 0.06 N.
  const double force_n[3] = {27.468535, 14.290895, 14.348390};
  const double deflection_rad[3] = {-0.002344186, 0.001169136, 0.001175051};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(hover.force_n(i), force_n[i], 1e-6);
    EXPECT_NEAR(hover.deflection_rad(i), deflection_rad[i], 1e-9);
    const ArmDescription& a = vehicle.arms[static_cast<size_t>(i)];
    // Small-angle check: b_i = (l_i f_i - m_p,i g L_i cos alpha_i) / k_i to 0.1 %.
    const double small_angle_rad = (a.ThrustLeverM() * hover.force_n(i) -
                                    a.tip_mass_kg * vehicle.gravity_m_s2 * a.length_m * std::cos(a.angle_rad)) /
                                   a.stiffness_n_m_rad;
    EXPECT_NEAR(hover.deflection_rad(i), small_angle_rad, 1e-3 * std::abs(small_angle_rad));
  }
  // Every generalized acceleration vanishes at (q0, 0, f).
  MultiCoords<double> q = MultiCoords<double>::Zero(6);
  q.tail(3) = hover.deflection_rad;
  const MultiCoords<double> acc =
      MultiArmAcceleration<double>(vehicle, q, MultiCoords<double>::Zero(6), ArmForces<double>(hover.force_n));
  EXPECT_LT(acc.cwiseAbs().maxCoeff(), 1e-9);
}

// Style rule 5: the Jet A and B against central differences of the
// accelerations at (q0, v0, f0).
void ExpectJacobiansMatchCentralDifferences(const VehicleDescription& vehicle, const Eigen::VectorXd& q0,
                                            const Eigen::VectorXd& v0, const Eigen::VectorXd& f0) {
  const int n = CoordinateCount(vehicle), arms = vehicle.arm_count;
  const MultiArmLinearModel lin = LinearizeMultiArm(vehicle, q0, v0, f0);
  Eigen::VectorXd point(2 * n + arms);
  point << q0, v0, f0;
  const auto derivative = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd dx(2 * n);
    dx.head(n) = x.segment(n, n);
    dx.tail(n) = MultiArmAcceleration<double>(vehicle, MultiCoords<double>(x.head(n)),
                                              MultiCoords<double>(x.segment(n, n)), ArmForces<double>(x.tail(arms)));
    return dx;
  };
  Eigen::MatrixXd numeric(2 * n, 2 * n + arms);
  for (int j = 0; j < 2 * n + arms; ++j) {
    const double step = 1e-6 * std::max(1.0, std::abs(point(j)));
    Eigen::VectorXd plus = point, minus = point;
    plus(j) += step;
    minus(j) -= step;
    numeric.col(j) = (derivative(plus) - derivative(minus)) / (2.0 * step);
  }
  Eigen::MatrixXd jet(2 * n, 2 * n + arms);
  jet << lin.a, lin.b;
  for (int r = 0; r < 2 * n; ++r) {
    const double scale = std::max(1.0, jet.row(r).cwiseAbs().maxCoeff());
    EXPECT_LT((jet.row(r) - numeric.row(r)).cwiseAbs().maxCoeff(), 1e-6 * scale) << "row " << r;
  }
}

TEST(MultiArmLinearization, JacobiansMatchCentralDifferencesAwayFromHover) {
  Eigen::VectorXd q0(6), v0(6), f0(3);
  q0 << 0.1, -0.2, 0.3, 0.004, -0.003, 0.002;
  v0 << 0.5, -0.4, 1.2, 0.3, -0.2, 0.1;
  f0 << 25.0, 18.0, 15.0;
  ExpectJacobiansMatchCentralDifferences(Trirotor(), q0, v0, f0);
}

// At the equilibrium q_ddot = 0: the case where a solver that skips zero
// right-hand sides (Eigen's triangular solves on Jets) loses the derivatives.
TEST(MultiArmLinearization, JacobiansMatchCentralDifferencesAtHover) {
  for (const VehicleDescription& vehicle : {Birotor(), Trirotor()}) {
    const MultiArmHover hover = SolveMultiArmHover(vehicle);
    const int n = CoordinateCount(vehicle);
    Eigen::VectorXd q0 = Eigen::VectorXd::Zero(n);
    q0.tail(vehicle.arm_count) = hover.deflection_rad;
    ExpectJacobiansMatchCentralDifferences(vehicle, q0, Eigen::VectorXd::Zero(n), hover.force_n);
  }
}

TEST(MultiArmLinearization, TrirotorArmModes) {
  const VehicleDescription vehicle = Trirotor();
  const std::vector<Mode> modes = OscillatoryModes(LinearizeMultiArmAtHover(vehicle, SolveMultiArmHover(vehicle)).a);
  ASSERT_EQ(modes.size(), 3u);
  // Printed by birotor-analyze --vehicle config/vehicles/trirotor.yaml (with d_i).
  const double frequency_hz[3] = {62.68506, 64.63204, 87.78903};
  const double damping_ratio[3] = {0.018734, 0.019316, 0.026236};
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(modes[i].frequency_hz, frequency_hz[i], 1e-4);
    EXPECT_NEAR(modes[i].damping_ratio, damping_ratio[i], 1e-6);
  }
}

}  // namespace
}  // namespace birotor
