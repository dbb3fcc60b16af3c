// The N-arm simulator and its autopilot (simulator/multi_arm_*): the trirotor
// flies from its file alone, a four-arm description built here flies with no
// code of its own, the birotor description tilts to move, a thrust loss on
// any rotor is held and one beyond the vehicle's rotors is refused.
#include "simulator/multi_arm_simulator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

VehicleDescription Trirotor() {
  return LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml");
}

// A fully actuated four-arm vehicle, not a shipped file: the trirotor's
// reference arms at 180, 0, -45 and -135 deg, thrust up on the first two and
// tilted by -45 and +45 deg (perpendicular to their arms) on the others.
VehicleDescription FourArms() {
  VehicleDescription vehicle;
  vehicle.name = "four arms (test)";
  vehicle.arm_count = 4;
  const double angle_deg[4] = {180.0, 0.0, -45.0, -135.0};
  const double thrust_deg[4] = {0.0, 0.0, -45.0, 45.0};
  for (int i = 0; i < 4; ++i) {
    ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
    arm.angle_rad = angle_deg[i] * M_PI / 180.0;
    arm.thrust_angle_rad = thrust_deg[i] * M_PI / 180.0;
    arm.spin = i % 2 == 0 ? 1 : -1;
  }
  return vehicle;
}

// A scenario for arm_count arms that holds the origin for duration_s, then
// (move_m != 0) a lateral move of move_m starting at 1 s taking move_s.
Scenario Hold(int arm_count, double duration_s, double move_m = 0.0, double move_s = 2.0) {
  Scenario scenario;
  scenario.name = "test";
  scenario.arm_count = arm_count;
  scenario.duration_s = duration_s;
  if (move_m != 0.0) {
    scenario.trajectory.kind = "waypoints";
    scenario.trajectory.waypoints.push_back(Waypoint{1.0, move_s, move_m, 0.0});
  }
  return scenario;
}

// Largest |phi| [rad], |x - x_ref| and |z - z_ref| [m] over the run, from
// from_s on, and the final position error [m].
struct Flight {
  double max_tilt_rad = 0.0;
  double max_x_error_m = 0.0;
  double max_z_error_m = 0.0;
  double final_error_m = 0.0;
  double max_x_m = 0.0;
};
Flight Fly(MultiArmSimulator* sim, double from_s = 0.0) {
  Flight flight;
  const VehicleDescription& v = sim->vehicle();
  while (sim->Step()) {
    if (sim->time_s() < from_s) continue;
    const MultiArmPlantState& x = sim->state();
    const Eigen::Vector2d error =
        Eigen::Vector2d(x(MultiArmQIndex(v, kX)), x(MultiArmQIndex(v, kZ))) - sim->reference().position_m;
    flight.max_tilt_rad = std::max(flight.max_tilt_rad, std::abs(x(MultiArmQIndex(v, kPhi))));
    flight.max_x_error_m = std::max(flight.max_x_error_m, std::abs(error.x()));
    flight.max_z_error_m = std::max(flight.max_z_error_m, std::abs(error.y()));
    flight.final_error_m = error.norm();
    flight.max_x_m = std::max(flight.max_x_m, x(MultiArmQIndex(v, kX)));
  }
  return flight;
}

// Bounds: the targets where it sets one, else the measured figure
// (seed 1, in the comment) times at most 1.5.
TEST(MultiArmSimulatorTest, TrirotorHoversLevelFromItsFile) {
  MultiArmSimulator sim(Trirotor(), Hold(3, 5.0));
  EXPECT_EQ(sim.mode(), MultiArmControlMode::kFullyActuated);
  const Flight flight = Fly(&sim);
  std::printf("trirotor hover 5 s: |phi| <= %.3g rad, |x| <= %.3g m, |z| <= %.3g m\n", flight.max_tilt_rad,
              flight.max_x_error_m, flight.max_z_error_m);
  EXPECT_LT(flight.max_tilt_rad, 0.01);     // the target; measured 0.0079 (turbulence)
  EXPECT_LT(flight.max_x_error_m, 0.004);   // measured 0.00266
  EXPECT_LT(flight.max_z_error_m, 0.0084);  // measured 0.0056
}

// The reference jumps by 1 m between two control periods (a 1 ms move):
// rotor 3 would go below 0 N, so the F_x increment is scaled down while the
// torque, allocated first, keeps the body level. The position integral (the
// cascade's Ki, as on the birotor) overshoots by 0.12 m and returns slowly.
TEST(MultiArmSimulatorTest, TrirotorLateralStepStaysLevel) {
  MultiArmSimulator sim(Trirotor(), Hold(3, 11.0, 1.0, 0.001));
  const Flight flight = Fly(&sim);
  std::printf("trirotor 1 m lateral step: |phi| <= %.3g rad, |z| <= %.3g m, x <= %.4g m, final error %.3g m\n",
              flight.max_tilt_rad, flight.max_z_error_m, flight.max_x_m, flight.final_error_m);
  EXPECT_LT(flight.max_tilt_rad, 0.02);     // the target; measured 0.0158
  EXPECT_LT(flight.max_z_error_m, 0.0174);  // measured 0.0116
  EXPECT_LT(flight.max_x_m, 1.18);          // measured 1.119
  EXPECT_LT(flight.final_error_m, 0.006);   // measured at 10 s after the step
}

TEST(MultiArmSimulatorTest, FourArmDescriptionBuiltHereHoversAndHolds) {
  const VehicleDescription vehicle = FourArms();
  ASSERT_TRUE(PlausibilityProblems(vehicle).empty());
  MultiArmSimulator sim(vehicle, Hold(4, 8.0, 0.5));
  EXPECT_EQ(sim.mode(), MultiArmControlMode::kFullyActuated);
  const Flight flight = Fly(&sim);
  std::printf("four arms, 0.5 m move in 2 s: |phi| <= %.3g rad, |x - x_ref| <= %.3g m, |z| <= %.3g m, final %.3g m\n",
              flight.max_tilt_rad, flight.max_x_error_m, flight.max_z_error_m, flight.final_error_m);
  EXPECT_LT(flight.max_tilt_rad, 0.01);     // the hover target; measured 0.00474
  EXPECT_LT(flight.max_x_error_m, 0.0086);  // measured 0.00572
  EXPECT_LT(flight.max_z_error_m, 0.009);   // measured 0.00601
  EXPECT_LT(flight.final_error_m, 0.0041);  // measured 0.00276
}

// N = 2: the birotor way, tilting to move.
TEST(MultiArmSimulatorTest, BirotorDescriptionTiltsToMove) {
  MultiArmSimulator sim(BirotorDescription(BirotorParams()), Hold(2, 8.0, 0.5));
  EXPECT_EQ(sim.mode(), MultiArmControlMode::kTiltToMove);
  const Flight flight = Fly(&sim);
  std::printf("birotor, 0.5 m move in 2 s: |phi| <= %.3g rad, final %.3g m\n", flight.max_tilt_rad,
              flight.final_error_m);
  EXPECT_GT(flight.max_tilt_rad, 0.063);  // it tilts to move; measured 0.0942
  EXPECT_LT(flight.max_tilt_rad, 0.14);
  EXPECT_LT(flight.final_error_m, 0.0035);  // measured 0.00231
}

TEST(MultiArmSimulatorTest, TrirotorHoldsAQuarterThrustLossOnRotor3) {
  Scenario scenario = Hold(3, 15.0);
  scenario.faults.thrust_steps.push_back(ThrustStep{5.0, 3, 0.75});
  MultiArmSimulator sim(Trirotor(), scenario);
  const Flight flight = Fly(&sim, 5.0);
  ASSERT_EQ(sim.fault_events().size(), 1u);
  EXPECT_EQ(sim.fault_events()[0].rotor, 3);
  EXPECT_NEAR(sim.input().thrust_scale[2], 0.75, 0.05);
  std::printf("trirotor, rotor 3 at 75 %% from 5 s: altitude deviation %.3g m, |x| %.3g m, |phi| %.3g rad\n",
              flight.max_z_error_m, flight.max_x_error_m, flight.max_tilt_rad);
  EXPECT_LT(flight.max_z_error_m, 0.1);    // the target; measured 0.067
  EXPECT_LT(flight.max_tilt_rad, 0.049);   // measured 0.0325
  EXPECT_LT(flight.max_x_error_m, 0.099);  // measured 0.0657
}

TEST(MultiArmSimulatorTest, ThrustStepBeyondTheRotorsIsRefused) {
  Scenario scenario = Hold(3, 1.0);
  scenario.faults.thrust_steps.push_back(ThrustStep{0.5, 4, 0.75});
  try {
    MultiArmSimulator sim(Trirotor(), scenario);
    FAIL() << "rotor 4 of a trirotor accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("faults.thrust_steps[0].rotor = 4: the vehicle has rotors 1 to 3"),
              std::string::npos)
        << e.what();
  }
}

// The scenario files' trajectories as the autopilot's reference.
TEST(MultiArmSimulatorTest, TrirotorFliesTheScenarioTrajectories) {
  // Measured |phi|, final error: gentle 0.00591 rad, 0.00086 m; aggressive
  // 0.00729 rad, 0.00734 m (the move ends 6 s before).
  for (const char* name : {"gentle", "aggressive"}) {
    const Scenario scenario =
        LoadScenario(std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml", {}, 3);
    MultiArmSimulator sim(Trirotor(), scenario);
    const Flight flight = Fly(&sim);
    std::printf("trirotor %s: |phi| <= %.3g rad, |x - x_ref| <= %.3g m, |z - z_ref| <= %.3g m, final %.3g m\n", name,
                flight.max_tilt_rad, flight.max_x_error_m, flight.max_z_error_m, flight.final_error_m);
    EXPECT_LT(flight.max_tilt_rad, 0.011) << name;
    EXPECT_LT(flight.final_error_m, 0.011) << name;
  }
}

}  // namespace
}  // namespace birotor
