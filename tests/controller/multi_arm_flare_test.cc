// The infeasible descent's flare for N rotors (controller/multi_arm_flare.h):
// on the birotor's description it is the birotor's FlareForcesFor; on the
// trirotor and the quadrotor its thrusts are the linear programme's
// optimum (no thrust vector within the bounds and the torque row makes
// more vertical force, checked against random ones), its torque within the
// budget's, and it makes more vertical force than any level allocation;
// bad input gives finite thrusts within the bounds.
#include "controller/multi_arm_flare.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "model/birotor_params.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

VehicleDescription Vehicle(const std::string& name) {
  return LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/" + name + ".yaml");
}

// The thrusts' world vertical force at tilt phi and pitch torque.
double VerticalN(const MultiArmFlareLimits& limits, const double* f, double phi_rad) {
  double total = 0.0;
  for (int i = 0; i < limits.rotor_count; ++i)
    total += f[i] * (std::sin(phi_rad) * limits.lateral[i] + std::cos(phi_rad) * limits.vertical[i]);
  return total;
}
double LateralN(const MultiArmFlareLimits& limits, const double* f) {
  double total = 0.0;
  for (int i = 0; i < limits.rotor_count; ++i) total += f[i] * limits.lateral[i];
  return total;
}
double TorqueNm(const MultiArmFlareLimits& limits, const double* f) {
  double total = 0.0;
  for (int i = 0; i < limits.rotor_count; ++i) total += f[i] * limits.torque_m[i];
  return total;
}

// A descent near the ground: 0.2 m up, sinking at 2 m/s, slightly tilted.
FlareState NearTheGround(double tilt_rad, double rate_rad_s) {
  FlareState state;
  state.height_m = 0.2;
  state.sink_rate_m_s = 2.0;
  state.tilt_rad = tilt_rad;
  state.pitch_rate_rad_s = rate_rad_s;
  return state;
}

// A fully actuated vehicle (the trirotor, the quadrotor) flares on its own
// budget, the birotor's description on the birotor's.
TEST(MultiArmFlareTest, AFullyActuatedVehicleTakesItsOwnTiltBudget) {
  EfficiencyParams params;
  params.flare_tilt_rad = 0.05;
  params.flare_tilt_fully_actuated_rad = 0.25;
  EXPECT_EQ(FlareTiltBudgetFor(BirotorDescription(BirotorParams()), params), 0.05);
  EXPECT_EQ(FlareTiltBudgetFor(Vehicle("birotor"), params), 0.05);
  EXPECT_EQ(FlareTiltBudgetFor(Vehicle("trirotor"), params), 0.25);
  EXPECT_EQ(FlareTiltBudgetFor(Vehicle("quadrotor"), params), 0.25);
}

TEST(MultiArmFlareTest, OnTheBirotorItIsTheBirotorsFlare) {
  const BirotorParams params;
  const VehicleDescription vehicle = BirotorDescription(params);
  MultiArmFlareLimits n_limits = FlareGeometryOf(vehicle, 0.08);
  FlareLimits limits;
  limits.tilt_budget_rad = 0.08;
  limits.min_time_to_go_s = params.motor_time_constant_s;
  limits.pitch_inertia_kg_m2 =
      params.body_inertia_kg_m2 + 2.0 * params.tip_mass_kg * params.arm_length_m * params.arm_length_m;
  limits.arm_length_m = params.arm_length_m;
  EXPECT_NEAR(n_limits.pitch_inertia_kg_m2, limits.pitch_inertia_kg_m2, 1e-12);
  EXPECT_DOUBLE_EQ(n_limits.min_time_to_go_s, limits.min_time_to_go_s);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> share(0.1, 1.0), tilt(-0.1, 0.1), rate(-1.0, 1.0), height(0.0, 0.3);
  const double max_n = params.thrust_coeff_n_s2_rad2 * params.omega_max_rad_s * params.omega_max_rad_s;
  for (int trial = 0; trial < 200; ++trial) {
    for (int i = 0; i < 2; ++i) limits.max_force_n[i] = n_limits.max_force_n[i] = share(random) * max_n;
    FlareState state = NearTheGround(tilt(random), rate(random));
    state.height_m = height(random);
    const FlareForces birotor = FlareForcesFor(state, limits);
    const MultiArmFlareForces n = MultiArmFlareForcesFor(state, n_limits);
    const double f1 = 0.5 * (birotor.total_force_n - birotor.force_difference_n);
    const double f2 = 0.5 * (birotor.total_force_n + birotor.force_difference_n);
    EXPECT_NEAR(n.force_n[0], f1, 1e-9) << trial;
    EXPECT_NEAR(n.force_n[1], f2, 1e-9) << trial;
    EXPECT_NEAR(n.time_to_go_s, birotor.time_to_go_s, 1e-12) << trial;
  }
}

// Every rotor's bound, the torque row, no body F_x (both vehicles are fully
// actuated) and the optimum: random thrust vectors within the bounds, with
// no F_x and a torque within [0, tau_want] towards the strong side, never
// make more vertical force.
TEST(MultiArmFlareTest, ItsThrustsAreTheProgrammesOptimum) {
  for (const std::string name : {"trirotor", "quadrotor"}) {
    const VehicleDescription vehicle = Vehicle(name);
    MultiArmFlareLimits limits = FlareGeometryOf(vehicle, 0.08);
    std::mt19937 random(38);
    std::uniform_real_distribution<double> share(0.0, 1.0), tilt(-0.1, 0.1), rate(-1.0, 1.0);
    for (int trial = 0; trial < 50; ++trial) {
      double strong_n_m = 0.0;
      for (int i = 0; i < vehicle.arm_count; ++i) {
        const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
        limits.max_force_n[i] = share(random) * arm.thrust_coeff_n_s2_rad2 * 1440000.0;
        strong_n_m += limits.torque_m[i] * limits.max_force_n[i];
      }
      const double sign = strong_n_m < 0.0 ? -1.0 : 1.0;
      const FlareState state = NearTheGround(tilt(random), rate(random));
      const MultiArmFlareForces flare = MultiArmFlareForcesFor(state, limits);
      const double t = flare.time_to_go_s;
      const double want_n_m =
          std::max(0.0, 2.0 * limits.pitch_inertia_kg_m2 *
                            (0.08 - sign * (state.tilt_rad + state.pitch_rate_rad_s * t)) / (t * t));
      ASSERT_NEAR(t, 0.1, 1e-12);
      for (int i = 0; i < vehicle.arm_count; ++i) {
        EXPECT_GE(flare.force_n[i], 0.0) << name << trial;
        EXPECT_LE(flare.force_n[i], limits.max_force_n[i] + 1e-9) << name << trial;
      }
      EXPECT_NEAR(flare.torque_n_m, TorqueNm(limits, flare.force_n), 1e-9);
      EXPECT_GE(sign * flare.torque_n_m, -1e-6) << name << trial;
      EXPECT_LE(sign * flare.torque_n_m, want_n_m + 1e-6) << name << trial;
      EXPECT_NEAR(flare.vertical_n, VerticalN(limits, flare.force_n, state.tilt_rad), 1e-9);
      // Fully actuated: no body F_x (the rotor with the largest |W_x,i| balances the others').
      EXPECT_TRUE(limits.holds_lateral);
      EXPECT_NEAR(LateralN(limits, flare.force_n), 0.0, 1e-6) << name << trial;
      int balancing = 0;
      for (int i = 1; i < vehicle.arm_count; ++i)
        if (std::fabs(limits.lateral[i]) > std::fabs(limits.lateral[balancing])) balancing = i;
      for (int sample = 0; sample < 4000; ++sample) {
        double f[kMaxArms] = {};
        for (int i = 0; i < vehicle.arm_count; ++i) f[i] = i == balancing ? 0.0 : share(random) * limits.max_force_n[i];
        f[balancing] = -LateralN(limits, f) / limits.lateral[balancing];
        if (f[balancing] < 0.0 || f[balancing] > limits.max_force_n[balancing]) continue;
        const double torque = sign * TorqueNm(limits, f);
        if (torque < 0.0 || torque > want_n_m) continue;
        EXPECT_LE(VerticalN(limits, f, state.tilt_rad), flare.vertical_n + 1e-9) << name << trial;
      }
    }
  }
}

// With no torque to spend (the tilt already at the budget) the flare is
// level: its torque is 0 and it still makes the most vertical force a
// level allocation can (every rotor at its bound but the one the torque
// row pins).
TEST(MultiArmFlareTest, WithTheBudgetSpentItFlaresLevel) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  MultiArmFlareLimits limits = FlareGeometryOf(vehicle, 0.08);
  for (int i = 0; i < vehicle.arm_count; ++i)
    limits.max_force_n[i] = (i == 0 ? 0.3 : 1.0) * vehicle.arms[static_cast<size_t>(i)].thrust_coeff_n_s2_rad2 * 1.44e6;
  double strong_n_m = 0.0;
  for (int i = 0; i < vehicle.arm_count; ++i) strong_n_m += limits.torque_m[i] * limits.max_force_n[i];
  const double sign = strong_n_m < 0.0 ? -1.0 : 1.0;
  const MultiArmFlareForces level = MultiArmFlareForcesFor(NearTheGround(sign * 0.08, 0.0), limits);
  EXPECT_NEAR(level.torque_n_m, 0.0, 1e-9);
  const MultiArmFlareForces flare = MultiArmFlareForcesFor(NearTheGround(0.0, 0.0), limits);
  std::printf(
      "trirotor, rotor 1 at 30 %%: level flare %.2f / %.2f / %.2f N (vertical %.2f N), budgeted %.2f / %.2f / "
      "%.2f N (vertical %.2f N, torque %.3f N m)\n",
      level.force_n[0], level.force_n[1], level.force_n[2], level.vertical_n, flare.force_n[0], flare.force_n[1],
      flare.force_n[2], flare.vertical_n, flare.torque_n_m);
  EXPECT_GT(flare.vertical_n, level.vertical_n);
  EXPECT_GT(sign * flare.torque_n_m, 0.0);
  EXPECT_DOUBLE_EQ(level.force_n[0], limits.max_force_n[0]);  // the weak rotor at its maximum
}

// Bad input: a non-finite tilt, rate, height or rotor bound, a negative
// bound or height: every thrust finite and within [0, u_i] (a non-finite or
// negative u_i counts as 0), never NaN.
TEST(MultiArmFlareTest, BadInputGivesFiniteThrustsWithinTheBounds) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (int c = 0; c < 6; ++c) {
    MultiArmFlareLimits limits = FlareGeometryOf(vehicle, 0.08);
    for (int i = 0; i < vehicle.arm_count; ++i) limits.max_force_n[i] = 40.0;
    FlareState state = NearTheGround(0.0, 0.0);
    if (c == 0) state.tilt_rad = nan;
    if (c == 1) state.pitch_rate_rad_s = inf;
    if (c == 2) state.height_m = nan;
    if (c == 3) state.height_m = -1.0;
    if (c == 4) limits.max_force_n[1] = nan;
    if (c == 5) limits.max_force_n[2] = -5.0;
    const MultiArmFlareForces flare = MultiArmFlareForcesFor(state, limits);
    for (int i = 0; i < vehicle.arm_count; ++i) {
      const double bound = std::isfinite(limits.max_force_n[i]) ? std::max(limits.max_force_n[i], 0.0) : 0.0;
      EXPECT_TRUE(std::isfinite(flare.force_n[i])) << c << " " << i;
      EXPECT_GE(flare.force_n[i], 0.0) << c << " " << i;
      EXPECT_LE(flare.force_n[i], bound) << c << " " << i;
    }
    EXPECT_TRUE(std::isfinite(flare.time_to_go_s)) << c;
  }
}

}  // namespace
}  // namespace birotor
