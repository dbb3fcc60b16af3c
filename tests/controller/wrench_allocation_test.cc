// The allocation of controller/wrench_allocation.h on the trirotor of
// config/vehicles/trirotor.yaml (W square: its inverse) and the birotor:
// a feasible wrench comes back exactly, every thrust stays within
// [0, e_i c_T,i omega_max^2], the torque is kept before F_z and F_z before
// F_x, and each speed is sqrt(f_i / (e_i c_T,i)).
#include "controller/wrench_allocation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "model/multi_arm_linearization.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

VehicleDescription Trirotor() {
  return LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml");
}

// c_T omega_max^2 = 4.6e-5 x 1200^2 [N] (every arm of both files).
constexpr double kMaxThrustN = 66.24;

// The wrench A (f - f_base) the thrusts make beyond the base [N, N, N m].
Eigen::Vector3d MadeWrench(const VehicleDescription& vehicle, const MultiArmRotorCommand& command,
                           const ArmForces<double>& base_n) {
  ArmForces<double> change_n(vehicle.arm_count);
  for (int i = 0; i < vehicle.arm_count; ++i) change_n(i) = command.force_n[static_cast<size_t>(i)] - base_n(i);
  return WrenchAllocation(vehicle) * change_n;
}

TEST(WrenchAllocationTest, ModesOfTheShippedVehicles) {
  EXPECT_EQ(MultiArmControlModeFor(Trirotor()), MultiArmControlMode::kFullyActuated);
  EXPECT_EQ(MultiArmControlModeFor(BirotorDescription(BirotorParams())), MultiArmControlMode::kTiltToMove);
}

TEST(WrenchAllocationTest, FeasibleWrenchComesBackExactly) {
  const VehicleDescription vehicle = Trirotor();
  const ArmForces<double> base_n = SolveMultiArmHover(vehicle).force_n;
  const WrenchAllocator allocator(vehicle, MultiArmControlMode::kFullyActuated);
  const Eigen::Vector3d wrench(2.0, 3.0, 0.5);
  const MultiArmRotorCommand command = allocator.Allocate(base_n, wrench, NominalEfficiencies());
  EXPECT_FALSE(command.saturated);
  EXPECT_LT((MadeWrench(vehicle, command, base_n) - wrench).norm(), 1e-9);
  for (int i = 0; i < 3; ++i) {
    const size_t r = static_cast<size_t>(i);
    EXPECT_NEAR(command.omega_cmd_rad_s[r], std::sqrt(command.force_n[r] / 4.6e-5), 1e-9) << i;
  }
}

// F_x = 30 N needs rotor 3 to lose 0.7071 x 30 = 21.2 N of its 14.32 N
// hover thrust (trirotor.yaml header): F_x is added at 14.32 / 21.21 = 0.675
// of the request, rotor 3 at 0 N, and the torque and F_z come back exactly.
TEST(WrenchAllocationTest, LateralForceGivesWayBeforeTorqueAndLift) {
  const VehicleDescription vehicle = Trirotor();
  const ArmForces<double> base_n = SolveMultiArmHover(vehicle).force_n;
  const WrenchAllocator allocator(vehicle, MultiArmControlMode::kFullyActuated);
  const Eigen::Vector3d wrench(30.0, 0.0, 0.0);
  const MultiArmRotorCommand command = allocator.Allocate(base_n, wrench, NominalEfficiencies());
  const Eigen::Vector3d made = MadeWrench(vehicle, command, base_n);
  EXPECT_TRUE(command.saturated);
  EXPECT_NEAR(made(kWrenchFx) / wrench(kWrenchFx), 0.675, 0.002);
  EXPECT_NEAR(made(kWrenchFz), 0.0, 1e-9);
  EXPECT_NEAR(made(kWrenchTorque), 0.0, 1e-9);
  EXPECT_NEAR(command.force_n[2], 0.0, 1e-9);
}

// A torque beyond reach: the torque takes what the bounds allow, F_z and
// F_x then get nothing that would push a thrust out, every thrust in bounds.
TEST(WrenchAllocationTest, TorqueBeyondReachKeepsEveryThrustInBounds) {
  const VehicleDescription vehicle = Trirotor();
  const ArmForces<double> base_n = SolveMultiArmHover(vehicle).force_n;
  const WrenchAllocator allocator(vehicle, MultiArmControlMode::kFullyActuated);
  const Eigen::Vector3d wrench(5.0, 10.0, 40.0);
  const MultiArmRotorCommand command = allocator.Allocate(base_n, wrench, NominalEfficiencies());
  const Eigen::Vector3d made = MadeWrench(vehicle, command, base_n);
  EXPECT_TRUE(command.saturated);
  EXPECT_GT(made(kWrenchTorque), 0.0);
  EXPECT_LT(made(kWrenchTorque), wrench(kWrenchTorque));
  for (int i = 0; i < 3; ++i) {
    EXPECT_GE(command.force_n[static_cast<size_t>(i)], 0.0) << i;
    EXPECT_LE(command.force_n[static_cast<size_t>(i)], kMaxThrustN + 1e-9) << i;
  }
}

// Rotor 1 at e = 0.6: its bound is 0.6 x 66.24 = 39.74 N. F_z = +30 N asks
// rotor 1 for 0.5858 x 30 = 17.57 N more than its 27.47 N hover thrust
// (45.04 N): nominal that fits, at 0.6 F_z is cut to (39.74 - 27.47) /
// 17.57 = 0.699 of the request, rotor 1 at its bound and omega_max.
TEST(WrenchAllocationTest, EfficiencySetsTheBoundAndTheSpeed) {
  const VehicleDescription vehicle = Trirotor();
  const ArmForces<double> base_n = SolveMultiArmHover(vehicle).force_n;
  const WrenchAllocator allocator(vehicle, MultiArmControlMode::kFullyActuated);
  const Eigen::Vector3d wrench(0.0, 30.0, 0.0);
  const MultiArmRotorCommand nominal = allocator.Allocate(base_n, wrench, NominalEfficiencies());
  EXPECT_FALSE(nominal.saturated);
  EXPECT_NEAR(nominal.force_n[0], 45.04, 0.02);
  RotorEfficiencies efficiency = NominalEfficiencies();
  efficiency[0] = 0.6;
  const MultiArmRotorCommand weak = allocator.Allocate(base_n, wrench, efficiency);
  EXPECT_TRUE(weak.saturated);
  EXPECT_NEAR(weak.force_n[0], 0.6 * kMaxThrustN, 1e-9);
  EXPECT_NEAR(weak.omega_cmd_rad_s[0], 1200.0, 1e-6);
  EXPECT_NEAR(MadeWrench(vehicle, weak, base_n)(kWrenchFz) / 30.0, 0.699, 0.002);
  EXPECT_NEAR(weak.omega_cmd_rad_s[1], std::sqrt(weak.force_n[1] / 4.6e-5), 1e-9);
}

// The trirotor's hover thrusts and its allocation along the fixed
// directions and with the re-solve at a bound (RedistributeAtBounds).
class WrenchRedistributionTest : public ::testing::Test {
 protected:
  WrenchRedistributionTest() { allocator.RedistributeAtBounds(true); }
  const VehicleDescription vehicle = Trirotor();
  const ArmForces<double> base_n = SolveMultiArmHover(vehicle).force_n;
  const WrenchAllocator fixed{vehicle, MultiArmControlMode::kFullyActuated};
  WrenchAllocator allocator{vehicle, MultiArmControlMode::kFullyActuated};
};

// RedistributeAtBounds: F_z = +10 N with rotor 2 1 N below its bound
// stops the fixed direction short; the rest goes to rotors 1 and 3 with the
// torque kept (rotors 2 and 3 alone could not: their levers and lift are
// alike), so F_z and the torque come back exactly and F_x gives way. With
// rotor 1 at its bound nothing is redistributed for the same reason, and
// within the bounds the answer is the fixed direction's, bit for bit.
TEST_F(WrenchRedistributionTest, FinishesLiftOnTheOtherRotors) {
  ASSERT_TRUE(allocator.redistributes());
  const Eigen::Vector3d feasible(2.0, 3.0, 0.5);
  const MultiArmRotorCommand same = allocator.Allocate(base_n, feasible, NominalEfficiencies());
  const MultiArmRotorCommand reference = fixed.Allocate(base_n, feasible, NominalEfficiencies());
  for (size_t r = 0; r < 3; ++r) EXPECT_EQ(same.force_n[r], reference.force_n[r]) << r;
  RotorEfficiencies efficiency = NominalEfficiencies();
  efficiency[1] = (base_n(1) + 1.0) / kMaxThrustN;
  const Eigen::Vector3d lift(0.0, 10.0, 0.0);
  const MultiArmRotorCommand weak = allocator.Allocate(base_n, lift, efficiency);
  const Eigen::Vector3d made = MadeWrench(vehicle, weak, base_n);
  EXPECT_TRUE(weak.saturated);
  EXPECT_NEAR(weak.force_n[1], base_n(1) + 1.0, 1e-9);
  EXPECT_NEAR(made(kWrenchFz), 10.0, 1e-9);
  EXPECT_NEAR(made(kWrenchTorque), 0.0, 1e-9);
  EXPECT_GT(std::fabs(made(kWrenchFx)), 1.0);
  for (size_t r = 0; r < 3; ++r) EXPECT_LE(weak.force_n[r], efficiency[r] * kMaxThrustN + 1e-9) << r;
  RotorEfficiencies weak_one = NominalEfficiencies();
  weak_one[0] = 0.6;  // bound 39.74 N: F_z = +30 N asks 45.04 N of rotor 1
  const MultiArmRotorCommand one = allocator.Allocate(base_n, Eigen::Vector3d(0.0, 30.0, 0.0), weak_one);
  const MultiArmRotorCommand one_fixed = fixed.Allocate(base_n, Eigen::Vector3d(0.0, 30.0, 0.0), weak_one);
  for (size_t r = 0; r < 3; ++r) EXPECT_EQ(one.force_n[r], one_fixed.force_n[r]) << r;
}

// Rotor 2 flown at its hover thrust's bound (e_2 = 14.32 / 66.24: a tilted
// hover's weak rotor): a pitch torque either way along the fixed direction
// needs rotor 2 up for one sign, which got none of it (the tilt ran away in
// closed loop); redistributed, rotors 1 and 3 make it and F_z, both signs.
TEST_F(WrenchRedistributionTest, MakesTheTorqueWithARotorAtItsBound) {
  RotorEfficiencies efficiency = NominalEfficiencies();
  efficiency[1] = base_n(1) / kMaxThrustN;
  double least_fixed_torque = 1.0;  // the smaller share of the request the fixed direction made [1]
  for (double torque : {-2.0, 2.0}) {
    const Eigen::Vector3d wrench(0.0, 0.0, torque);
    const Eigen::Vector3d made = MadeWrench(vehicle, allocator.Allocate(base_n, wrench, efficiency), base_n);
    EXPECT_NEAR(made(kWrenchTorque), torque, 1e-9) << torque;
    EXPECT_NEAR(made(kWrenchFz), 0.0, 1e-9) << torque;
    const Eigen::Vector3d along_fixed = MadeWrench(vehicle, fixed.Allocate(base_n, wrench, efficiency), base_n);
    least_fixed_torque = std::min(least_fixed_torque, along_fixed(kWrenchTorque) / torque);
  }
  EXPECT_LT(least_fixed_torque, 1e-9);
  // The birotor's mode has nothing to redistribute onto: the switch stays off.
  WrenchAllocator birotor(BirotorDescription(BirotorParams()), MultiArmControlMode::kTiltToMove);
  birotor.RedistributeAtBounds(true);
  EXPECT_FALSE(birotor.redistributes());
}

// N = 2: no F_x column; F_z and the torque come back exactly.
TEST(WrenchAllocationTest, BirotorMakesLiftAndTorqueOnly) {
  const VehicleDescription vehicle = BirotorDescription(BirotorParams());
  const ArmForces<double> base_n = SolveMultiArmHover(vehicle).force_n;
  const WrenchAllocator allocator(vehicle, MultiArmControlMode::kTiltToMove);
  EXPECT_EQ(allocator.inverse().col(kWrenchFx).norm(), 0.0);
  const MultiArmRotorCommand command =
      allocator.Allocate(base_n, Eigen::Vector3d(7.0, 4.0, 0.3), NominalEfficiencies());
  const Eigen::Vector3d made = MadeWrench(vehicle, command, base_n);
  EXPECT_NEAR(made(kWrenchFz), 4.0, 1e-9);
  EXPECT_NEAR(made(kWrenchTorque), 0.3, 1e-9);
}

}  // namespace
}  // namespace birotor
