// The N-arm plant (model/multi_arm_plant.h): the birotor description's plant
// is the birotor plant of model/plant.h (one physics), and the hover state of
// the trirotor file is a fixed point of the plant.
#include "model/multi_arm_plant.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "model/arm_dynamics.h"
#include "model/bench_dynamics.h"
#include "model/equilibrium.h"
#include "model/plant.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

constexpr double kStepS = 0.00025;  // the scenarios' RK4 step [s]

// Varying commands (through the clamp at both ends) and unequal thrust scales,
// so every term of the two plants is exercised, over 1 s from a perturbed
// hover: the states agree entry by entry at every step. The two dynamics
// differ only in the order of floating-point operations (multi_arm_dynamics.h
// sums the arms' terms; birotor_dynamics.h writes them out), so the
// difference is rounding: measured 3.2e-15 of any entry (relative to
// max(1, |entry|)); the bound leaves room for other compilers.
TEST(MultiArmPlantTest, BirotorDescriptionIsTheBirotorPlant) {
  const BirotorParams params;
  const VehicleDescription vehicle = BirotorDescription(params);
  PlantState birotor = HoverPlantState(SolveHoverEquilibrium(params));
  birotor(kPlantQ + kPhi) = 0.05;
  birotor(kPlantV + kX) = 0.3;
  birotor(kPlantV + kB1) = 0.01;
  ASSERT_EQ(MultiArmPlantSize(vehicle), kPlantStateSize);  // same layout: [q, v, omega_1, omega_2]
  MultiArmPlantState multi = birotor;

  double worst = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const double t = k * kStepS;
    PlantInput u;
    u.omega_cmd_rad_s[0] = 700.0 + 600.0 * std::sin(2.0 * M_PI * 3.0 * t);  // below 0 .. above omega_max
    u.omega_cmd_rad_s[1] = 700.0 + 200.0 * std::cos(2.0 * M_PI * 5.0 * t) - 800.0 * (t > 0.6);
    u.thrust_scale[0] = 0.9;
    u.thrust_scale[1] = 1.05;
    MultiArmPlantInput multi_u;
    for (int i = 0; i < 2; ++i) {
      multi_u.omega_cmd_rad_s[static_cast<size_t>(i)] = u.omega_cmd_rad_s[i];
      multi_u.thrust_scale[static_cast<size_t>(i)] = u.thrust_scale[i];
    }
    birotor = StepPlant(params, birotor, u, kStepS);
    multi = StepMultiArmPlant(vehicle, multi, multi_u, kStepS);
    for (int j = 0; j < kPlantStateSize; ++j) {
      const double scale = std::max(1.0, std::abs(birotor(j)));
      worst = std::max(worst, std::abs(multi(j) - birotor(j)) / scale);
      ASSERT_NEAR(multi(j), birotor(j), 1e-12 * scale) << "entry " << j << " at t = " << t;
    }
  }
  EXPECT_GT(std::abs(birotor(kPlantQ + kX)), 0.1);  // it did move
  std::printf("worst relative difference over 1 s: %.3g\n", worst);
}

// The trirotor of config/vehicles/trirotor.yaml at SolveMultiArmHover's state,
// commanded its hover speeds, stays level and still. The exact hover thrusts
// (measured: 27.4685, 14.2909, 14.3484 N) differ from the rigid allocation of
// docs/vehicle-description.md (27.9534, 13.9767, 13.9767 N) by the tip
// weights' moment about the centre, g m_p L sum_i cos alpha_i = 0.293 N m
// (levers -L, L, L: f_2 + f_3 - f_1 = 1.17 N), and by the deflected thrusts.
TEST(MultiArmPlantTest, HoverThrustsHoldTheTrirotorLevel) {
  const VehicleDescription vehicle =
      LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml");
  const MultiArmHover hover = SolveMultiArmHover(vehicle);
  ASSERT_TRUE(hover.converged);
  EXPECT_NEAR(hover.force_n(0), 27.4685, 1e-4);
  EXPECT_NEAR(hover.force_n(1), 14.2909, 1e-4);
  EXPECT_NEAR(hover.force_n(2), 14.3484, 1e-4);
  MultiArmPlantState x = MultiArmHoverPlantState(vehicle, hover);
  MultiArmPlantInput u;
  for (int i = 0; i < 3; ++i) u.omega_cmd_rad_s[static_cast<size_t>(i)] = x(MultiArmOmegaIndex(vehicle, i));
  double worst_phi_rad = 0.0, worst_position_m = 0.0;
  for (int k = 0; k < 4000; ++k) {
    x = StepMultiArmPlant(vehicle, x, u, kStepS);
    worst_phi_rad = std::max(worst_phi_rad, std::abs(x(MultiArmQIndex(vehicle, kPhi))));
    worst_position_m = std::max(
        {worst_position_m, std::abs(x(MultiArmQIndex(vehicle, kX))), std::abs(x(MultiArmQIndex(vehicle, kZ)))});
  }
  std::printf("trirotor hover over 1 s: |phi| <= %.3g rad, |x|, |z| <= %.3g m\n", worst_phi_rad, worst_position_m);
  EXPECT_LT(worst_phi_rad, 1e-9);
  EXPECT_LT(worst_position_m, 1e-9);
}

// The supported plant (bench, or the ground under a landed vehicle) of the
// birotor description is model/bench_dynamics.h's ClampedBodyDerivative:
// the same arm rows (m_p L^2 b_ddot + d b_dot + k b + s m_p g L cos b = s L f)
// summed in another order, so agreement to rounding (measured 0 to 1e-16
// relative); and MultiArmStaticDeflectionRad, exact in cos b, is the
// birotor's small-angle StaticDeflectionRad to the cos b ~ 1 relative error
// (b ~ 3e-3 rad: b^2 / 2 ~ 5e-6 of the weight term).
TEST(MultiArmPlantTest, BirotorDescriptionOnTheSupportIsTheBenchPlant) {
  const BirotorParams params;
  const VehicleDescription vehicle = BirotorDescription(params);
  PlantState x = PlantState::Zero();
  x(kPlantQ + kB1) = -2.0e-3;
  x(kPlantQ + kB2) = 3.0e-3;
  x(kPlantV + kB1) = 0.4;
  x(kPlantV + kB2) = -0.2;
  x(kPlantOmega1) = 650.0;
  x(kPlantOmega2) = 720.0;
  PlantInput u;
  u.omega_cmd_rad_s[0] = 900.0;
  u.omega_cmd_rad_s[1] = 400.0;
  u.thrust_scale[0] = 0.95;
  u.thrust_scale[1] = 1.02;
  MultiArmPlantInput multi_u;
  for (int i = 0; i < 2; ++i) {
    multi_u.omega_cmd_rad_s[static_cast<size_t>(i)] = u.omega_cmd_rad_s[i];
    multi_u.thrust_scale[static_cast<size_t>(i)] = u.thrust_scale[i];
  }
  const PlantState bench = ClampedBodyDerivative(params, x, u);
  const MultiArmPlantState multi = MultiArmSupportedDerivative(vehicle, MultiArmPlantState(x), multi_u);
  for (int j = 0; j < kPlantStateSize; ++j)
    EXPECT_NEAR(multi(j), bench(j), 1e-12 * std::max(1.0, std::abs(bench(j)))) << "entry " << j;
  for (int arm = 0; arm < 2; ++arm) {
    for (double force_n : {0.0, 10.0, 25.0}) {
      const double small_angle = StaticDeflectionRad(params, arm, force_n);
      EXPECT_NEAR(MultiArmStaticDeflectionRad(vehicle, arm, force_n), small_angle, 1e-5 * std::abs(small_angle) + 1e-12)
          << "arm " << arm << ", " << force_n << " N";
    }
  }
  // At the root the supported arm is at rest: b_ddot = 0 (trirotor, rotor 3 at 12 N).
  const VehicleDescription trirotor =
      LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml");
  MultiArmPlantState rest = MultiArmPlantState::Zero(MultiArmPlantSize(trirotor));
  MultiArmPlantInput rest_u;
  const double omega3 = std::sqrt(12.0 / trirotor.arms[2].thrust_coeff_n_s2_rad2);
  rest(MultiArmOmegaIndex(trirotor, 2)) = omega3;
  rest_u.omega_cmd_rad_s[2] = omega3;
  for (int i = 0; i < 3; ++i) {
    const double force_n = i == 2 ? 12.0 : 0.0;
    rest(MultiArmQIndex(trirotor, DeflectionIndex(i))) = MultiArmStaticDeflectionRad(trirotor, i, force_n);
  }
  const MultiArmPlantState rate = MultiArmSupportedDerivative(trirotor, rest, rest_u);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(rate(MultiArmVIndex(trirotor, DeflectionIndex(i))), 0.0, 1e-9) << i;
}

// The one-arm clamped row of model/arm_dynamics.h (the bench fit's
// residual, identification/clamped_arm_residual.h) is each arm's row of the
// supported plant, on every arm of the trirotor at a deflected, moving state,
// and the birotor's own clamped row for BirotorClampedArm.
TEST(MultiArmPlantTest, ClampedArmRowIsTheSupportedPlantRow) {
  const VehicleDescription trirotor =
      LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml");
  MultiArmPlantState x = MultiArmPlantState::Zero(MultiArmPlantSize(trirotor));
  MultiArmPlantInput u;
  const double deflection[3] = {-4.0e-3, 2.5e-3, 6.0e-3}, rate[3] = {0.3, -0.5, 0.2}, omega[3] = {700, 450, 820};
  for (int i = 0; i < 3; ++i) {
    x(MultiArmQIndex(trirotor, DeflectionIndex(i))) = deflection[i];
    x(MultiArmVIndex(trirotor, DeflectionIndex(i))) = rate[i];
    x(MultiArmOmegaIndex(trirotor, i)) = omega[i];
  }
  const MultiArmPlantState x_dot = MultiArmSupportedDerivative(trirotor, x, u);
  for (int i = 0; i < 3; ++i) {
    const ArmDescription& a = trirotor.arms[static_cast<size_t>(i)];
    const double force_n = a.thrust_coeff_n_s2_rad2 * omega[i] * omega[i];
    const double row =
        ClampedArmAcceleration<double>(ClampedArmOf(trirotor, i), a.stiffness_n_m_rad, a.damping_n_m_s_rad,
                                       a.tip_mass_kg, deflection[i], rate[i], force_n);
    const double plant = x_dot(MultiArmVIndex(trirotor, DeflectionIndex(i)));
    EXPECT_NEAR(row, plant, 1e-9 * std::abs(plant)) << "arm " << i + 1;
  }
  const BirotorParams p;
  for (int arm = 0; arm < 2; ++arm) {
    const double birotor = ClampedArmAcceleration<double>(p, arm, p.arm_stiffness_n_m_rad, p.arm_damping_n_m_s_rad,
                                                          p.tip_mass_kg, 3.0e-3, -0.4, 12.0);
    const double general = ClampedArmAcceleration<double>(BirotorClampedArm(p, arm), p.arm_stiffness_n_m_rad,
                                                          p.arm_damping_n_m_s_rad, p.tip_mass_kg, 3.0e-3, -0.4, 12.0);
    EXPECT_NEAR(general, birotor, 1e-12 * std::abs(birotor)) << "arm " << arm + 1;
  }
}

}  // namespace
}  // namespace birotor
