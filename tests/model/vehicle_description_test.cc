// The N-arm vehicle description: the birotor both ways, the allocation, the
// hover and the plausibility rules (docs/vehicle-description.md).
#include "model/vehicle_description.h"

#include <gtest/gtest.h>

#include <limits>

namespace birotor {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// Every BirotorParams field away from its default, so a field mapped to the
// wrong place shows.
BirotorParams Distinct() {
  BirotorParams p;
  p.body_mass_kg = 4.1;
  p.tip_mass_kg = 0.3;
  p.arm_length_m = 0.26;
  p.body_inertia_kg_m2 = 0.051;
  p.arm_stiffness_n_m_rad = 2700.0;
  p.arm_damping_n_m_s_rad = 0.27;
  p.gravity_m_s2 = 9.8;
  p.thrust_coeff_n_s2_rad2 = 4.7e-5;
  p.motor_time_constant_s = 0.036;
  p.omega_max_rad_s = 1250.0;
  p.turbulence_std = 0.02;
  p.turbulence_corr_time_s = 0.2;
  p.gauge_scale[0] = 1.1;
  p.gauge_scale[1] = 0.9;
  p.gauge_offset_rad[0] = 1e-4;
  p.gauge_offset_rad[1] = -2e-4;
  p.gauge_offset_std_rad = 6e-5;
  p.gauge_drift_psd_rad2_s = 2e-10;
  return p;
}

// The four-arm vehicle of PlausibleFourArms: two birotor-like arms tilted
// 30 deg outward, two more at 150 and 30 deg with the thrust perpendicular.
VehicleDescription FourArms() {
  VehicleDescription d;
  d.name = "four_arms";
  d.arm_count = 4;
  const double angle_deg[4] = {180.0, 0.0, 150.0, 30.0};
  const double thrust_angle_deg[4] = {30.0, -30.0, -30.0, 30.0};
  for (size_t i = 0; i < 4; ++i) {
    d.arms[i].angle_rad = angle_deg[i] * kDeg;
    d.arms[i].thrust_angle_rad = thrust_angle_deg[i] * kDeg;
    d.arms[i].spin = (i % 2 == 0) ? 1 : -1;
  }
  return d;
}

bool Mentions(const std::vector<std::string>& problems, const std::string& text) {
  for (const std::string& p : problems) {
    if (p.find(text) != std::string::npos) return true;
  }
  return false;
}

std::string Joined(const std::vector<std::string>& problems) {
  std::string out;
  for (const std::string& p : problems) out += p + "\n";
  return out;
}

TEST(VehicleDescription, BirotorMapsEveryFieldBothWays) {
  const BirotorParams p = Distinct();
  const VehicleDescription d = BirotorDescription(p);
  ASSERT_EQ(d.arm_count, 2);
  EXPECT_DOUBLE_EQ(d.arms[0].angle_rad, kPi);  // arm 1 along body -x (docs/interface.md)
  EXPECT_DOUBLE_EQ(d.arms[1].angle_rad, 0.0);
  EXPECT_DOUBLE_EQ(d.arms[0].ThrustLeverM(), -0.26);  // -L: the s_1 L of model/birotor_dynamics.h
  EXPECT_DOUBLE_EQ(d.arms[1].ThrustLeverM(), 0.26);
  EXPECT_DOUBLE_EQ(d.arms[1].gauge_scale, 0.9);
  EXPECT_DOUBLE_EQ(d.arms[1].gauge_offset_rad, -2e-4);
  EXPECT_DOUBLE_EQ(d.TotalMass(), p.TotalMass());
  BirotorParams back;
  std::string why;
  ASSERT_TRUE(ToBirotorParams(d, &back, &why)) << why;
  // Every field round-trips: the description of the result is the same.
  EXPECT_EQ(FirstDifference(BirotorDescription(back), d), "");
  EXPECT_DOUBLE_EQ(back.gauge_drift_psd_rad2_s, 2e-10);
  EXPECT_DOUBLE_EQ(back.turbulence_corr_time_s, 0.2);
}

TEST(VehicleDescription, NotABirotorSaysWhy) {
  BirotorParams out;
  std::string why;
  VehicleDescription d = BirotorDescription(BirotorParams());
  d.arms[1].stiffness_n_m_rad = 3000.0;
  EXPECT_FALSE(ToBirotorParams(d, &out, &why));
  EXPECT_NE(why.find("arms[1].stiffness_n_m_rad: 3000 vs 2628"), std::string::npos) << why;
  d = BirotorDescription(BirotorParams());
  d.arms[0].has_gauge = false;
  EXPECT_FALSE(ToBirotorParams(d, &out, &why));
  EXPECT_NE(why.find("arms[0].has_gauge"), std::string::npos) << why;
  d = BirotorDescription(BirotorParams());
  d.arms[1].thrust_angle_rad = 0.1;
  EXPECT_FALSE(ToBirotorParams(d, &out, &why));
  EXPECT_NE(why.find("arms[1].thrust_angle_rad"), std::string::npos) << why;
  EXPECT_FALSE(ToBirotorParams(FourArms(), &out, &why));
  EXPECT_NE(why.find("arm_count is 4"), std::string::npos) << why;
  // -pi is pi: the angle is compared modulo 2 pi.
  d = BirotorDescription(BirotorParams());
  d.arms[0].angle_rad = -kPi;
  EXPECT_TRUE(ToBirotorParams(d, &out, &why)) << why;
}

TEST(VehicleDescription, BirotorAllocationHoverAndMargin) {
  const VehicleDescription d = BirotorDescription(BirotorParams());
  const AllocationMatrix a = WrenchAllocation(d);
  ASSERT_EQ(a.cols(), 2);
  // Thrust up at both tips; torque -L f1 + L f2 (tau of model/birotor_dynamics.h).
  EXPECT_DOUBLE_EQ(a(kWrenchFx, 0), 0.0);
  EXPECT_DOUBLE_EQ(a(kWrenchFz, 1), 1.0);
  EXPECT_DOUBLE_EQ(a(kWrenchTorque, 0), -0.25);
  EXPECT_DOUBLE_EQ(a(kWrenchTorque, 1), 0.25);
  // Hover of shared/spec/reference-vehicle.md: 22.4465 N and 698.55 rad/s per rotor.
  const HoverSolution hover = SolveHover(d);
  EXPECT_NEAR(hover.thrust_n[0], BirotorParams().HoverForceN(), 1e-12);
  EXPECT_NEAR(hover.thrust_n[1], 22.4465, 5e-5);
  EXPECT_NEAR(hover.omega_rad_s[0], 698.55, 0.01);
  // [F_z; torque / L] = [[1, 1], [-1, 1]] f: both singular values sqrt(2).
  const AllocationMargin margin = ControlledAxesMargin(d);
  EXPECT_EQ(margin.rows, 2);
  EXPECT_NEAR(margin.singular_values(0), std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(margin.ratio, 1.0, 1e-12);
  EXPECT_TRUE(PlausibilityProblems(d).empty()) << Joined(PlausibilityProblems(d));
}

// N = 2 with unequal tips: the F_z and torque rows f_1 + f_2 = W and
// L (f_2 - f_1) = g L (m_p,2 - m_p,1) (the tip weights' moment) give
// f_2 - f_1 = g (0.5 - 0.28812) = 2.07854 N about the mean W / 2.
TEST(VehicleDescription, HoverCancelsTheTipWeightsMoment) {
  VehicleDescription d = BirotorDescription(BirotorParams());
  d.arms[1].tip_mass_kg = 0.5;
  const double weight_n = 9.81 * (4.0 + 0.28812 + 0.5);
  const Eigen::Vector3d wrench = HoverWrench(d);
  EXPECT_NEAR(wrench(kWrenchFz), weight_n, 1e-12);
  EXPECT_NEAR(wrench(kWrenchTorque), 9.81 * 0.25 * (0.5 - 0.28812), 1e-12);
  const HoverSolution hover = SolveHover(d);
  EXPECT_NEAR(hover.thrust_n[1] - hover.thrust_n[0], 2.07854, 1e-5);
  EXPECT_NEAR(hover.thrust_n[0] + hover.thrust_n[1], weight_n, 1e-9);
  // The symmetric birotor: cos pi + cos 0 cancels exactly, no moment.
  EXPECT_EQ(HoverWrench(BirotorDescription(BirotorParams()))(kWrenchTorque), 0.0);
}

TEST(VehicleDescription, PlausibleFourArms) {
  const VehicleDescription d = FourArms();
  EXPECT_TRUE(PlausibilityProblems(d).empty()) << Joined(PlausibilityProblems(d));
  // Levers (-cos 30, cos 30, -1, 1) L sum to 0 and the F_x row (-1, 1, 1, -1)/2
  // too: the least-norm hover is four equal thrusts g (m + 4 m_p) / (4 cos 30 deg).
  const double each_n = 9.81 * (4.0 + 4 * 0.28812) / (4.0 * std::cos(30.0 * kDeg));
  const HoverSolution hover = SolveHover(d);
  for (size_t i = 0; i < 4; ++i) EXPECT_NEAR(hover.thrust_n[i], each_n, 1e-9) << i;
  EXPECT_NEAR(hover.omega_rad_s[0], std::sqrt(each_n / 4.6e-5), 1e-6);
  EXPECT_EQ(ControlledAxesMargin(d).rows, 3);
}

TEST(VehicleDescription, TooHeavyBirotorCannotHover) {
  BirotorParams p;
  p.body_mass_kg = 400.0;
  // f = 9.81 (400 + 2 x 0.28812) / 2 = 1964.83 N; sqrt(1964.83 / 4.6e-5) = 6535.57 rad/s > 1200.
  const std::vector<std::string> problems = PlausibilityProblems(BirotorDescription(p));
  ASSERT_EQ(problems.size(), 2u) << Joined(problems);
  EXPECT_TRUE(Mentions(problems, "rotor 1 needs 1964.83 N, speed 6535.57 rad/s above omega_max_rad_s 1200"))
      << Joined(problems);
  EXPECT_TRUE(Mentions(problems, "(allowed: hover speed <= omega_max_rad_s)")) << Joined(problems);
}

TEST(VehicleDescription, ArmCountOutsideTwoToSix) {
  VehicleDescription d = FourArms();
  d.arm_count = 7;
  EXPECT_TRUE(Mentions(PlausibilityProblems(d), "arm_count: 7 arms (allowed: [2, 6])"));
  // The helpers stay inside the six arms of the array.
  EXPECT_EQ(WrenchAllocation(d).cols(), 0);
  EXPECT_EQ(ControlledAxesMargin(d).rows, 0);
  EXPECT_EQ(SolveHover(d).thrust_n[0], 0.0);
  d.arm_count = 1;
  EXPECT_TRUE(Mentions(PlausibilityProblems(d), "arm_count: 1 arms (allowed: [2, 6])"));
}

TEST(VehicleDescription, NonFiniteAndNonPositiveFields) {
  VehicleDescription d = FourArms();
  d.body_mass_kg = std::numeric_limits<double>::quiet_NaN();
  d.arms[2].tip_mass_kg = 0.0;
  d.arms[3].spin = 0;
  const std::vector<std::string> problems = PlausibilityProblems(d);
  EXPECT_TRUE(Mentions(problems, "body_mass_kg: nan kg is not a positive finite number (allowed: > 0 kg)"))
      << Joined(problems);
  EXPECT_TRUE(Mentions(problems, "arms[2].tip_mass_kg: 0 kg is not a positive finite number")) << Joined(problems);
  EXPECT_TRUE(Mentions(problems, "arms[3].spin: 0 (allowed: 1 or -1)")) << Joined(problems);
}

TEST(VehicleDescription, AllThrustUpHasNoLateralAxis) {
  // Three rotors all thrusting up: the F_x row is zero, rank 2 of 3.
  VehicleDescription d = FourArms();
  d.arm_count = 3;
  for (size_t i = 0; i < 3; ++i) d.arms[i].thrust_angle_rad = 0.0;
  const std::vector<std::string> problems = PlausibilityProblems(d);
  ASSERT_EQ(problems.size(), 1u) << Joined(problems);
  EXPECT_TRUE(Mentions(problems, "allocation: the thrusts reach F_x, F_z and the torque")) << Joined(problems);
  EXPECT_TRUE(Mentions(problems, "(allowed: >= 0.1; the arms' angle_rad and thrust_angle_rad)")) << Joined(problems);
}

TEST(VehicleDescription, GaugeOnAnArmWithoutLever) {
  VehicleDescription d = FourArms();
  // Arm 3 at 150 deg with the thrust along the arm (theta = alpha - 90 deg): l = 0.
  d.arms[2].thrust_angle_rad = 60.0 * kDeg;
  const std::vector<std::string> problems = PlausibilityProblems(d);
  EXPECT_TRUE(Mentions(problems, "arms[2].has_gauge: true on an arm whose thrust lever")) << Joined(problems);
  EXPECT_TRUE(Mentions(problems, "(allowed: |l| >= 0.1 x length_m, or has_gauge false)")) << Joined(problems);
  d.arms[2].has_gauge = false;
  EXPECT_FALSE(Mentions(PlausibilityProblems(d), "has_gauge")) << Joined(PlausibilityProblems(d));
}

TEST(VehicleDescription, NegativeHoverThrustIsNamed) {
  // A birotor whose right rotor thrusts down (u_2 = [0, -1], l_2 = -L): the
  // torque row -L f1 - L f2 = 0 and F_z f1 - f2 = W give f2 = -W / 2.
  VehicleDescription d = BirotorDescription(BirotorParams());
  d.arms[1].thrust_angle_rad = kPi;
  const std::vector<std::string> problems = PlausibilityProblems(d);
  EXPECT_TRUE(Mentions(problems, "hover: rotor 2 would need thrust -22.4465 N (allowed: > 0 N")) << Joined(problems);
}

}  // namespace
}  // namespace birotor
