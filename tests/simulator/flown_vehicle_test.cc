// The vehicle a scenario flies on a description (simulator/flown_vehicle.h):
// a scenario whose vehicle: section is the reference birotor's flies the
// description bit for bit; a mismatch scenario changes every arm of any
// vehicle by its ratio to the reference (the trirotor's arms 20 % stiffer
// on mismatch_stiffness_plus20), and the simulator flies that vehicle.
#include "simulator/flown_vehicle.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "model/vehicle_description_checksum.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "simulator/multi_arm_simulator.h"
#include "tests/simulator/test_support.h"

namespace birotor {
namespace {

VehicleDescription Trirotor() {
  return LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml");
}

Scenario ForArms(const std::string& name, int arm_count, const std::vector<std::string>& overrides = {}) {
  return LoadScenario(ScenarioPath(name), overrides, arm_count);
}

TEST(FlownVehicleTest, AReferenceSectionFliesTheDescriptionBitForBit) {
  const VehicleDescription trirotor = Trirotor();
  for (const char* name : {"hover", "gentle", "aggressive", "thrust_loss", "bench"}) {
    const VehicleDescription flown = FlownVehicle(trirotor, ForArms(name, 3).vehicle);
    EXPECT_EQ(DescriptionChecksum(flown), DescriptionChecksum(trirotor))
        << name << ": " << FirstDifference(flown, trirotor);
  }
}

TEST(FlownVehicleTest, AMismatchScenarioChangesEveryArmByItsRatio) {
  const VehicleDescription trirotor = Trirotor();
  // mismatch_all: body +15 %, tip mass +20 %, stiffness +20 %, c_T +20 %, tau_m +30 %.
  // (Its true gauges are a birotor's list, 0.7 and 1.0: three given here.)
  const Scenario scenario = ForArms("mismatch_all", 3, {"gauge.scale=[0.7, 1.0, 1.0]"});
  const VehicleDescription flown = FlownVehicle(trirotor, scenario.vehicle);
  EXPECT_NEAR(flown.body_mass_kg, 1.15 * trirotor.body_mass_kg, 1e-12);
  EXPECT_DOUBLE_EQ(flown.body_inertia_kg_m2, trirotor.body_inertia_kg_m2);
  EXPECT_DOUBLE_EQ(flown.turbulence_std, trirotor.turbulence_std);
  for (size_t i = 0; i < 3; ++i) {
    const ArmDescription& arm = trirotor.arms[i];
    const ArmDescription& out = flown.arms[i];
    EXPECT_NEAR(out.stiffness_n_m_rad, 1.2 * arm.stiffness_n_m_rad, 1e-9) << "arm " << i + 1;
    EXPECT_NEAR(out.tip_mass_kg, 1.2 * arm.tip_mass_kg, 1e-12) << "arm " << i + 1;
    EXPECT_NEAR(out.thrust_coeff_n_s2_rad2, 1.2 * arm.thrust_coeff_n_s2_rad2, 1e-15) << "arm " << i + 1;
    EXPECT_NEAR(out.motor_time_constant_s, 1.3 * arm.motor_time_constant_s, 1e-12) << "arm " << i + 1;
    // What the scenario does not change, and what an estimator believes.
    EXPECT_EQ(out.angle_rad, arm.angle_rad);
    EXPECT_EQ(out.thrust_angle_rad, arm.thrust_angle_rad);
    EXPECT_EQ(out.length_m, arm.length_m);
    EXPECT_EQ(out.damping_n_m_s_rad, arm.damping_n_m_s_rad);
    EXPECT_EQ(out.gauge_scale, arm.gauge_scale);
    EXPECT_EQ(out.has_gauge, arm.has_gauge);
  }
}

// On the birotor's own description the scenario's section is the flown
// vehicle exactly, as the birotor's simulator flies it.
TEST(FlownVehicleTest, TheBirotorDescriptionFliesTheScenarioSectionExactly) {
  const VehicleDescription birotor = BirotorDescription(BirotorParams());
  for (const char* name : {"mismatch_all", "mismatch_payload_plus15", "mismatch_stiffness_minus20"}) {
    const Scenario scenario = ForArms(name, 2);
    EXPECT_EQ(DescriptionChecksum(FlownVehicle(birotor, scenario.vehicle)), DescriptionChecksum(scenario.vehicle))
        << name;
  }
}

TEST(FlownVehicleTest, TheSimulatorFliesTheChangedVehicle) {
  const VehicleDescription trirotor = Trirotor();
  const MultiArmSimulator nominal(trirotor, ForArms("gentle", 3));
  MultiArmSimulator heavier(trirotor, ForArms("mismatch_payload_plus15", 3));
  EXPECT_NEAR(heavier.vehicle().body_mass_kg, 1.15 * trirotor.body_mass_kg, 1e-12);
  ASSERT_TRUE(heavier.hover().converged);
  // Its hover carries the heavier weight: total thrust up by the weight's
  // ratio within 1 % (the thrust directions are the description's).
  const double weight_ratio = heavier.vehicle().TotalMass() / trirotor.TotalMass();
  EXPECT_NEAR(heavier.hover().force_n.sum() / nominal.hover().force_n.sum(), weight_ratio, 0.01 * weight_ratio);
  // And it starts there (within the turbulence of the first step).
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(heavier.TrueForce(i), heavier.hover().force_n(i), 0.05 * heavier.hover().force_n(i))
        << "rotor " << i + 1;
  }
}

}  // namespace
}  // namespace birotor
