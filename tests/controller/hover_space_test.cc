// The hovers of controller/hover_space.h: none to spare on the birotor and
// the trirotor, one on the quadrotor of config/vehicles/quadrotor.yaml; the
// nearest hover in a box keeps the controlled wrench, meets its bounds and
// is optimal (a grid on the quadrotor's one spare direction; the
// Karush-Kuhn-Tucker conditions, checked independently, on six rotors), and
// HoverFeasibility holds the quadrotor's hovers that the least-norm
// hover's per-rotor bounds declared infeasible.
#include "controller/hover_space.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "controller/hover_feasibility.h"
#include "model/multi_arm_linearization.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

VehicleDescription Vehicle(const std::string& name) {
  return LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/" + name + ".yaml");
}

HoverSpace SpaceOf(const VehicleDescription& vehicle) {
  const ArmForces<double> hover_n = SolveMultiArmHover(vehicle).force_n;
  return HoverSpace(vehicle, MultiArmControlModeFor(vehicle), hover_n);
}

// c_T omega_max^2 of every arm of the files [N].
constexpr double kMaxThrustN = 66.24;

// The quadrotor with rotor 1 at e_1 and the others nominal [1].
std::array<double, kMaxArms> Efficiencies(double e1) {
  std::array<double, kMaxArms> e;
  e.fill(1.0);
  e[0] = e1;
  return e;
}

// HoverFeasibility on the quadrotor's four rotors and its hovers.
HoverFeasibility QuadrotorFeasibility(const EfficiencyParams& params, const HoverSpace& space) {
  double max_n[kMaxArms] = {};
  double hover_n[kMaxArms] = {};
  for (int i = 0; i < 4; ++i) {
    max_n[i] = kMaxThrustN;
    hover_n[i] = space.hover_force_n()(i);
  }
  return HoverFeasibility(params, 4, max_n, hover_n, space);
}

// W_r (f - f_hover): what a hover of the space changes on the controlled rows [N, N, N m].
Eigen::Vector3d ControlledChange(const VehicleDescription& vehicle, const ArmForces<double>& f,
                                 const ArmForces<double>& hover_n) {
  return WrenchAllocation(vehicle) * (f - hover_n);
}

TEST(HoverSpaceTest, TheBirotorAndTheTrirotorHaveNoneToSpare) {
  for (const char* name : {"birotor", "trirotor"}) {
    const VehicleDescription vehicle = Vehicle(name);
    const HoverSpace space = SpaceOf(vehicle);
    EXPECT_EQ(space.spare_rotors(), 0) << name;
    ArmForces<double> hover_n;
    EXPECT_TRUE(space.NearestWithinShares(Efficiencies(1.0).data(), 0.05, 0.8, &hover_n)) << name;
    for (int i = 0; i < vehicle.arm_count; ++i) EXPECT_EQ(hover_n(i), space.hover_force_n()(i)) << name;
    // Rotor 1 below its least-norm hover thrust: nothing else holds the vehicle.
    const double share = space.hover_force_n()(0) / kMaxThrustN;
    EXPECT_FALSE(space.NearestWithinShares(Efficiencies(0.9 * share).data(), 0.0, 1.0, &hover_n)) << name;
    EXPECT_EQ(space.tilts(), std::string(name) == "trirotor") << name;  // fully actuated
    EXPECT_EQ(space.rebalances(), space.tilts()) << name;
  }
}

// The trirotor has no rotor to spare but may hover tilted: its thrusts at
// tilt phi are cos(phi) f_hover + sin(phi) f_lateral, f_lateral = [0,
// +35.7, -35.7] N (rotors 2 and 3 lean sideways, rotor 1 does not). Rotor 2
// at 20 % (13.25 N, below its level 14.32 N) hovers 0.04 rad off level;
// rotor 2 at 5 % or dead needs more than 0.2 rad (dead: 0.40 rad); rotor 1's
// share barely moves with the tilt (cos only), so rotor 1 at 30 % holds none.
TEST(HoverSpaceTest, TheTrirotorHoversTiltedWhenRotorTwoCannotHoldItsLevelShare) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const HoverSpace space = SpaceOf(vehicle);
  const double weight_n = vehicle.TotalMass() * vehicle.gravity_m_s2;
  const double max_share = 1.0 / 1.02;
  std::array<double, kMaxArms> e = Efficiencies(1.0);
  e[1] = 0.2;
  ArmForces<double> f;
  EXPECT_FALSE(space.NearestWithinShares(e.data(), 0.0, max_share, &f));
  double tilt_rad = 0.0;
  ASSERT_TRUE(space.NearestTiltedWithinShares(e.data(), 0.1, max_share, 0.2, &f, &tilt_rad));
  std::printf("trirotor, rotor 2 at 20 %%: tilt %+.3f rad, thrusts %.2f %.2f %.2f N\n", tilt_rad, f(0), f(1), f(2));
  EXPECT_NEAR(std::fabs(tilt_rad), 0.04, 0.006);
  EXPECT_LE(f(1), max_share * 0.2 * kMaxThrustN + 1e-9);
  // cos(phi) W f_hover + sin(phi) [m g, 0, 0] (W f_hover: the rigid rows of
  // the elastic hover, with the arms' deflection torque).
  const Eigen::Vector3d wrench = WrenchAllocation(vehicle) * f;
  const Eigen::Vector3d level = WrenchAllocation(vehicle) * space.hover_force_n();
  EXPECT_NEAR(wrench(kWrenchFx), level(kWrenchFx) * std::cos(tilt_rad) + weight_n * std::sin(tilt_rad), 1e-6);
  EXPECT_NEAR(wrench(kWrenchFz), level(kWrenchFz) * std::cos(tilt_rad), 1e-6);
  EXPECT_NEAR(wrench(kWrenchTorque), level(kWrenchTorque) * std::cos(tilt_rad), 1e-6);
  // The cascade's box (spare_max_share 0.8: room above rotor 2 for its torque) tilts further.
  ASSERT_TRUE(space.NearestTiltedWithinShares(e.data(), 0.1, 0.8, 0.2, &f, &tilt_rad));
  std::printf("trirotor, rotor 2 at 20 %%, within 0.8: tilt %+.3f rad, thrusts %.2f %.2f %.2f N\n", tilt_rad, f(0),
              f(1), f(2));
  EXPECT_NEAR(std::fabs(tilt_rad), 0.11, 0.006);
  EXPECT_LE(f(1), 0.8 * 0.2 * kMaxThrustN + 1e-9);
  for (double weak : {0.05, 0.0}) {
    e[1] = weak;
    EXPECT_FALSE(space.NearestTiltedWithinShares(e.data(), 0.05, max_share, 0.2, &f, &tilt_rad)) << weak;
  }
  e = Efficiencies(0.3);  // rotor 1 at 30 %
  EXPECT_FALSE(space.NearestTiltedWithinShares(e.data(), 0.05, max_share, 0.2, &f, &tilt_rad));
}

// A dead rotor's box has no width: the trirotor holds rotor 2 (or 3) at
// exactly 0 N at the one tilt where cos(phi) h_2 + sin(phi) l_2 = 0 (0.40
// rad; rotors 1 and 3 then carry 25.3 and 26.4 N), found exactly, not on a
// grid; below that tilt, none.
TEST(HoverSpaceTest, TheTrirotorHoldsADeadRotorAtItsOneTilt) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const HoverSpace space = SpaceOf(vehicle);
  const double weight_n = vehicle.TotalMass() * vehicle.gravity_m_s2;
  const Eigen::Vector3d level = WrenchAllocation(vehicle) * space.hover_force_n();
  for (int dead : {1, 2}) {
    std::array<double, kMaxArms> e = Efficiencies(1.0);
    e[static_cast<size_t>(dead)] = 0.0;
    ArmForces<double> f;
    double tilt_rad = 0.0;
    ASSERT_TRUE(space.NearestTiltedWithinShares(e.data(), 0.1, 0.8, 0.45, &f, &tilt_rad)) << dead;
    std::printf("trirotor, rotor %d dead: tilt %+.4f rad, thrusts %.2f %.2f %.2f N\n", dead + 1, tilt_rad, f(0), f(1),
                f(2));
    EXPECT_EQ(f(dead), 0.0) << dead;
    EXPECT_NEAR(std::fabs(tilt_rad), 0.40, 0.005) << dead;
    EXPECT_LT(tilt_rad * (dead == 1 ? 1.0 : -1.0), 0.0) << dead;  // the two dead rotors tilt opposite ways
    const Eigen::Vector3d wrench = WrenchAllocation(vehicle) * f;
    EXPECT_NEAR(wrench(kWrenchFx), level(kWrenchFx) * std::cos(tilt_rad) + weight_n * std::sin(tilt_rad), 1e-6);
    EXPECT_NEAR(wrench(kWrenchFz), level(kWrenchFz) * std::cos(tilt_rad), 1e-6);
    EXPECT_NEAR(wrench(kWrenchTorque), level(kWrenchTorque) * std::cos(tilt_rad), 1e-6);
    for (int i = 0; i < 3; ++i) {
      if (i == dead) continue;
      EXPECT_GE(f(i), 0.1 * kMaxThrustN) << dead << " " << i;
      EXPECT_LE(f(i), 0.8 * kMaxThrustN) << dead << " " << i;
    }
    EXPECT_FALSE(space.NearestTiltedWithinShares(e.data(), 0.1, 0.8, 0.38, &f, &tilt_rad)) << dead;
  }
}

TEST(HoverSpaceTest, TheQuadrotorKeepsItsLeastNormHoverWhileItFits) {
  const VehicleDescription vehicle = Vehicle("quadrotor");
  const HoverSpace space = SpaceOf(vehicle);
  EXPECT_EQ(space.spare_rotors(), 1);
  ArmForces<double> hover_n;
  ASSERT_TRUE(space.NearestWithinShares(Efficiencies(0.6).data(), 0.05, 0.8, &hover_n));
  for (int i = 0; i < 4; ++i) EXPECT_EQ(hover_n(i), space.hover_force_n()(i));  // bit for bit
}

// Rotor 1 at 20 %: its least-norm share (16.8 N) is above 0.8 x 13.2 N, so
// the hover moves along the spare direction until rotor 1 sits at its
// bound; rotors 3 and 4 take the rest. The grid over that direction finds
// nothing nearer.
TEST(HoverSpaceTest, AWeakRotorHandsItsShareToTheOthers) {
  const VehicleDescription vehicle = Vehicle("quadrotor");
  const HoverSpace space = SpaceOf(vehicle);
  const ArmForces<double>& hover = space.hover_force_n();
  ArmForces<double> f;
  ASSERT_TRUE(space.NearestWithinShares(Efficiencies(0.2).data(), 0.05, 0.8, &f));
  EXPECT_LT(ControlledChange(vehicle, f, hover).norm(), 1e-9);
  EXPECT_NEAR(f(0), 0.8 * 0.2 * kMaxThrustN, 1e-9);
  EXPECT_GT(f(2), hover(2));
  EXPECT_GT(f(3), hover(3));
  for (int i = 1; i < 4; ++i) {
    EXPECT_GE(f(i), 0.05 * kMaxThrustN);
    EXPECT_LE(f(i), 0.8 * kMaxThrustN);
  }
  // The spare direction z (unit): f = hover + t z; every grid point in the box is at least as far.
  Eigen::VectorXd z = f - hover;
  const double distance_n = z.norm();
  z /= distance_n;
  const double high_n[4] = {0.8 * 0.2 * kMaxThrustN, 0.8 * kMaxThrustN, 0.8 * kMaxThrustN, 0.8 * kMaxThrustN};
  const double low_n[4] = {0.05 * 0.2 * kMaxThrustN, 0.05 * kMaxThrustN, 0.05 * kMaxThrustN, 0.05 * kMaxThrustN};
  double nearest_n = 1e9;
  for (double t = -60.0; t <= 60.0; t += 1e-3) {
    bool inside = true;
    for (int i = 0; i < 4; ++i) inside = inside && hover(i) + t * z(i) >= low_n[i] && hover(i) + t * z(i) <= high_n[i];
    if (inside) nearest_n = std::min(nearest_n, std::fabs(t));
  }
  EXPECT_NEAR(nearest_n, distance_n, 2e-3);
}

// A dead rotor 1 pins rotor 2 at 0 too (the quadrotor's hovers have f_1 =
// f_2): no hover keeps rotor 2 above 5 %; with no lower share rotors 3 and
// 4 carry the vehicle alone.
TEST(HoverSpaceTest, ADeadRotorLeavesItsPartnerNoRoom) {
  const VehicleDescription vehicle = Vehicle("quadrotor");
  const HoverSpace space = SpaceOf(vehicle);
  ArmForces<double> f;
  EXPECT_FALSE(space.NearestWithinShares(Efficiencies(0.0).data(), 0.05, 1.0, &f));
  ASSERT_TRUE(space.NearestWithinShares(Efficiencies(0.0).data(), 0.0, 1.0, &f));
  EXPECT_NEAR(f(0), 0.0, 1e-9);
  EXPECT_NEAR(f(1), 0.0, 1e-6);
  EXPECT_NEAR(f(2), f(3), 1e-6);
  EXPECT_LT(ControlledChange(vehicle, f, space.hover_force_n()).norm(), 1e-9);
}

// Six rotors (the quadrotor's four and two more at +-100 deg), random boxes:
// every answer keeps the controlled wrench, meets the box, and satisfies
// f - f_hover = W_r^T nu + sum over the active bounds of c_i e_i with c_i
// <= 0 at an upper and >= 0 at a lower bound (the optimality conditions of
// the nearest point, solved here by least squares, not by the code under test).
TEST(HoverSpaceTest, SixRotorsMeetTheOptimalityConditions) {
  VehicleDescription vehicle = Vehicle("quadrotor");
  vehicle.arm_count = 6;
  vehicle.arms[4] = vehicle.arms[0];
  vehicle.arms[4].angle_rad = 100.0 * M_PI / 180.0;
  vehicle.arms[4].thrust_angle_rad = 10.0 * M_PI / 180.0;
  vehicle.arms[5] = vehicle.arms[0];
  vehicle.arms[5].angle_rad = -100.0 * M_PI / 180.0;
  vehicle.arms[5].thrust_angle_rad = -20.0 * M_PI / 180.0;
  const HoverSpace space = SpaceOf(vehicle);
  ASSERT_EQ(space.spare_rotors(), 3);
  const ArmForces<double>& hover = space.hover_force_n();
  const Eigen::MatrixXd w = WrenchAllocation(vehicle);
  std::mt19937 random(38);
  std::uniform_real_distribution<double> efficiency(0.05, 1.0);
  int answered = 0;
  int with_active_bounds = 0;
  for (int trial = 0; trial < 200; ++trial) {
    double e[kMaxArms];
    for (double& v : e) v = efficiency(random);
    ArmForces<double> f;
    if (!space.NearestWithinShares(e, 0.05, 0.8, &f)) continue;
    ++answered;
    EXPECT_LT((w * (f - hover)).norm(), 1e-8) << trial;
    Eigen::MatrixXd basis(6, 3 + 6);
    basis.leftCols(3) = w.transpose();
    int columns = 3;
    int kind[6] = {};  // +1 at the upper bound, -1 at the lower, 0 inside
    for (int i = 0; i < 6; ++i) {
      const double makes_n = e[i] * kMaxThrustN;
      EXPECT_GE(f(i), 0.05 * makes_n - 1e-9) << trial;
      EXPECT_LE(f(i), 0.8 * makes_n + 1e-9) << trial;
      kind[i] = std::fabs(f(i) - 0.8 * makes_n) < 1e-7 ? 1 : std::fabs(f(i) - 0.05 * makes_n) < 1e-7 ? -1 : 0;
      if (kind[i] != 0) basis.col(columns++) = Eigen::VectorXd::Unit(6, i);
    }
    with_active_bounds += columns > 3 ? 1 : 0;
    const Eigen::MatrixXd a = basis.leftCols(columns);
    const Eigen::VectorXd d = f - hover;
    const Eigen::VectorXd c = a.completeOrthogonalDecomposition().solve(d);
    EXPECT_LT((a * c - d).norm(), 1e-7) << trial;
    for (int i = 0, k = 3; i < 6; ++i) {
      if (kind[i] == 0) continue;
      if (kind[i] > 0) EXPECT_LE(c(k), 1e-7) << trial << " rotor " << i;
      if (kind[i] < 0) EXPECT_GE(c(k), -1e-7) << trial << " rotor " << i;
      ++k;
    }
  }
  std::printf("six rotors: %d of 200 boxes hold a hover, %d of them with active bounds\n", answered,
              with_active_bounds);
  EXPECT_GT(answered, 50);
  EXPECT_GT(with_active_bounds, 25);
}

// HoverFeasibility on the quadrotor: every rotor at 25 % holds the vehicle
// (f_1 = f_2 = a, f_3 = f_4 = b with 2 a + 1.414 b = 50.55 N, each within
// 16.2 N), though 25 % is below rotor 1's least-norm bound 0.259; at 15 %
// no hover exists (at most 33 N) and it is infeasible after infeasible_s.
TEST(HoverSpaceTest, TheQuadrotorHoversWhereTheLeastNormBoundGaveUp) {
  const VehicleDescription vehicle = Vehicle("quadrotor");
  const HoverSpace space = SpaceOf(vehicle);
  const EfficiencyParams params;
  for (const double e : {0.25, 0.15}) {
    HoverFeasibility feasibility = QuadrotorFeasibility(params, space);
    EXPECT_GT(feasibility.FeasibilityBound(0), 0.25);
    FeasibilityInputs in;
    for (int i = 0; i < 4; ++i) in.efficiency[i] = e;
    for (int k = 0; k < 40; ++k) feasibility.Update(in, 0.005);
    EXPECT_EQ(feasibility.infeasible(), e < 0.2) << e;
  }
}

// A rotor flown at FORCE's floor (e = 0.2, "at most") on the quadrotor:
// rotors 3 and 4 pair (f_3 = f_4), so with rotor 3 at 20 % a level hover
// exists; when FORCE's reports below the floor say it makes nothing, rotor 4
// would have to stop too: level only (spare_hover_tilt_rad 0) the check
// says infeasible; with the default tilt rotor 4 keeps its 5 % and the body
// tilts against its lateral force (feasible).
TEST(HoverSpaceTest, AReportBelowTheFloorIsTakenOverTheFloor) {
  const VehicleDescription vehicle = Vehicle("quadrotor");
  const HoverSpace space = SpaceOf(vehicle);
  for (const double tilt_rad : {0.0, EfficiencyParams().spare_hover_tilt_rad}) {
    for (const double report : {kNaNReport, 0.1, 0.0}) {
      EfficiencyParams params;
      params.spare_hover_tilt_rad = tilt_rad;
      HoverFeasibility feasibility = QuadrotorFeasibility(params, space);
      FeasibilityInputs in;
      in.efficiency[2] = 0.2;
      in.below_floor_report[2] = report;
      for (int k = 0; k < 40; ++k) feasibility.Update(in, 0.005);
      EXPECT_EQ(feasibility.infeasible(), report == 0.0 && tilt_rad == 0.0) << report << " " << tilt_rad;
    }
  }
}

// Any one dead rotor of the quadrotor: no level hover keeps the others
// within [5 %, 1 / 1.02] (its partner would have to stop), but a tilted one
// does. Its thrusts make the weight along the tilted vertical with no
// torque, W f = [m g sin phi, F_z,hover cos phi, 0], within the box, the dead rotor at
// 0, and no smaller tilt on the grid holds one (the least |phi|). The tilt
// balances the 5 % its partner keeps: sin phi = 0.707 x 0.05 x 66.24 N / m g
// = 0.046 rad, the grid's next step 0.050.
TEST(HoverSpaceTest, ADeadRotorIsHeldByATiltedHover) {
  const VehicleDescription vehicle = Vehicle("quadrotor");
  const HoverSpace space = SpaceOf(vehicle);
  const double weight_n = vehicle.TotalMass() * vehicle.gravity_m_s2;
  const double min_share = 0.05;
  const double max_share = 1.0 / 1.02;
  for (int dead = 0; dead < 4; ++dead) {
    std::array<double, kMaxArms> e = Efficiencies(1.0);
    e[static_cast<size_t>(dead)] = 0.0;
    ArmForces<double> f;
    EXPECT_FALSE(space.NearestWithinShares(e.data(), min_share, max_share, &f)) << dead;
    double tilt_rad = 0.0;
    ASSERT_TRUE(space.NearestTiltedWithinShares(e.data(), min_share, max_share, 0.1, &f, &tilt_rad)) << dead;
    std::printf("quadrotor, rotor %d dead: tilt %+.3f rad, thrusts %.2f %.2f %.2f %.2f N\n", dead + 1, tilt_rad, f(0),
                f(1), f(2), f(3));
    EXPECT_NEAR(std::fabs(tilt_rad), 0.050, 1e-9) << dead;
    // cos(phi) W f_hover + sin(phi) [m g, 0, 0] (W f_hover: the rigid rows of
    // the elastic hover, [0, m g - 0.016 N, 0]).
    const Eigen::Vector3d level = WrenchAllocation(vehicle) * space.hover_force_n();
    const Eigen::Vector3d wrench = WrenchAllocation(vehicle) * f;
    EXPECT_NEAR(wrench(kWrenchFx), weight_n * std::sin(tilt_rad), 1e-6) << dead;
    EXPECT_NEAR(wrench(kWrenchFz), level(kWrenchFz) * std::cos(tilt_rad), 1e-6) << dead;
    EXPECT_NEAR(wrench(kWrenchTorque), 0.0, 1e-6) << dead;
    EXPECT_EQ(f(dead), 0.0) << dead;
    for (int i = 0; i < 4; ++i) {
      if (i == dead) continue;
      EXPECT_GE(f(i), min_share * kMaxThrustN - 1e-9) << dead << " " << i;
      EXPECT_LE(f(i), max_share * kMaxThrustN + 1e-9) << dead << " " << i;
    }
    EXPECT_FALSE(space.NearestTiltedWithinShares(e.data(), min_share, max_share, 0.045, &f, &tilt_rad)) << dead;
    // The cascade's base keeps the partner at 10 % (spare_tilted_min_share): twice the tilt.
    ASSERT_TRUE(space.NearestTiltedWithinShares(e.data(), 0.1, max_share, 0.2, &f, &tilt_rad)) << dead;
    EXPECT_NEAR(std::fabs(tilt_rad), 0.095, 1e-9) << dead;
  }
}

// MultiArmLaw::AnyHover's shortcut is exact: every box HoverBase tries lies
// within its widest one, so a grid started at the widest box's least tilt
// finds the same tilt and hover as one started at 0, and no hover in the
// widest box means none in any (random efficiencies on the quadrotor, a
// quarter of the rotors dead).
TEST(HoverSpaceTest, AWiderBoxsLeastTiltStartsEveryNarrowerSearch) {
  const VehicleDescription vehicle = Vehicle("quadrotor");
  const HoverSpace space = SpaceOf(vehicle);
  const double widest = 1.0 / 1.02, max_tilt_rad = 0.2;
  std::mt19937 random(38);
  std::uniform_real_distribution<double> share(0.0, 1.2);
  int tilted = 0, none = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::array<double, kMaxArms> e = Efficiencies(1.0);
    for (int i = 0; i < 4; ++i) e[static_cast<size_t>(i)] = share(random) < 0.3 ? 0.0 : share(random);
    double least_rad = 0.0;
    const bool level = space.NearestWithinShares(e.data(), 0.05, widest, nullptr);
    const bool any =
        level || space.NearestTiltedWithinShares(e.data(), 0.05, widest, max_tilt_rad, nullptr, &least_rad);
    least_rad = std::fabs(least_rad);
    tilted += any && !level;
    none += !any;
    for (double max_share : {0.8, widest}) {
      for (double min_share : {0.1, 0.05}) {
        ArmForces<double> from_zero, from_least;
        double tilt_zero = 0.0, tilt_least = 0.0;
        const bool found =
            space.NearestTiltedWithinShares(e.data(), min_share, max_share, max_tilt_rad, &from_zero, &tilt_zero);
        EXPECT_TRUE(any || !found) << trial;
        ASSERT_EQ(space.NearestTiltedWithinShares(e.data(), min_share, max_share, max_tilt_rad, &from_least,
                                                  &tilt_least, least_rad),
                  found)
            << trial;
        if (!found) continue;
        EXPECT_EQ(tilt_least, tilt_zero) << trial;
        for (int i = 0; i < 4; ++i) EXPECT_EQ(from_least(i), from_zero(i)) << trial << " " << i;
      }
    }
  }
  std::printf("300 efficiency sets: %d held only tilted, %d held no hover\n", tilted, none);
  EXPECT_GT(tilted, 10);
  EXPECT_GT(none, 10);
}

// Whether a level hover can pitch the body either way (the MPC's choice of
// plan, MultiArmController::MpcPlansTilted): with rotor 1 (or 2) dead every
// level hover pins its partner at 0 and the three live rotors make a pure
// torque only one way (checked independently: their unique thrust change
// for +tau, W_live^-1 [0, 0, tau], moves the partner one way, so -tau needs
// it below 0); with rotor 3 (or 4) dead rotors 1 and 2 pitch both ways.
TEST(HoverSpaceTest, ALevelHoverPitchesBothWaysUnlessAnUpperRotorIsDead) {
  const VehicleDescription vehicle = Vehicle("quadrotor");
  const HoverSpace space = SpaceOf(vehicle);
  const double max_share = 1.0 / 1.02;
  const double torque_n_m = 0.12;  // about 1 rad/s^2 on the quadrotor's rigid pitch inertia
  EXPECT_TRUE(space.LevelPitchesBothWays(Efficiencies(1.0).data(), max_share, torque_n_m));
  const bool expected[4] = {false, false, true, true};
  for (int dead = 0; dead < 4; ++dead) {
    std::array<double, kMaxArms> e = Efficiencies(1.0);
    e[static_cast<size_t>(dead)] = 0.0;
    EXPECT_EQ(space.LevelPitchesBothWays(e.data(), max_share, torque_n_m), expected[dead]) << dead;
  }
  // Rotor 1 dead: the live rotors 2, 3, 4 span the three rows alone.
  const Eigen::MatrixXd w = WrenchAllocation(vehicle);
  const Eigen::Matrix3d live = w.rightCols<3>();
  const Eigen::Vector3d change = live.fullPivLu().solve(Eigen::Vector3d(0.0, 0.0, torque_n_m));
  EXPECT_GT(std::fabs(change(0)), 1e-3);  // rotor 2 moves, either way it is at 0
  // A live rotor at 5 % of its map (what the MPC flies a dead rotor at) would
  // pitch both ways: the caller counts such a rotor as making nothing.
  EXPECT_TRUE(space.LevelPitchesBothWays(Efficiencies(0.05).data(), max_share, torque_n_m));
  // The birotor (none to spare) pitches both ways about its one hover.
  const HoverSpace birotor = SpaceOf(Vehicle("birotor"));
  EXPECT_TRUE(birotor.LevelPitchesBothWays(Efficiencies(1.0).data(), max_share, torque_n_m));
}

// The birotor tilts to move: it has no lateral force of its own, so no
// tilted hover (its tilt is the position loop's).
TEST(HoverSpaceTest, ATiltToMoveVehicleHasNoTiltedHover) {
  const VehicleDescription vehicle = Vehicle("birotor");
  const HoverSpace space = SpaceOf(vehicle);
  ArmForces<double> f;
  double tilt_rad = 0.0;
  const std::array<double, kMaxArms> e = Efficiencies(1.0);
  EXPECT_TRUE(space.NearestWithinShares(e.data(), 0.05, 0.8, &f));
  EXPECT_FALSE(space.NearestTiltedWithinShares(e.data(), 0.05, 0.8, 0.1, &f, &tilt_rad));
}

}  // namespace
}  // namespace birotor
