// The allocation of controller/wrench_allocation.h on the trirotor of
// config/vehicles/trirotor.yaml (W square: its inverse) and the birotor:
// a feasible wrench comes back exactly, every thrust stays within
// [0, e_i c_T,i omega_max^2], the torque is kept before F_z and F_z before
// F_x, and each speed is sqrt(f_i / (e_i c_T,i)).
#include "controller/wrench_allocation.h"

#include <gtest/gtest.h>

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
