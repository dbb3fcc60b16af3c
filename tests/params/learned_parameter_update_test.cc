// Learned strain scales, body mass and tip mass into the vehicle parameters
// (params/learned_parameter_update.h): what is written where, and every
// refusal naming the file, the key and the range. Values from
// config/reference_vehicle.yaml (gauge_scale [1, 1], body_mass_kg 4.0,
// tip_mass_kg 0.28812) and the estimator's shipped priors (0.1, 0.15, 0.15).
#include "params/learned_parameter_update.h"

#include <gtest/gtest.h>

#include <limits>

namespace birotor {
namespace {

LearnedVehicleValues LearnedScales(double g1, double g2, double sigma) {
  LearnedVehicleValues learned;
  learned.has_strain_scale = true;
  learned.strain_scale[0] = g1;
  learned.strain_scale[1] = g2;
  learned.strain_scale_std[0] = learned.strain_scale_std[1] = sigma;
  return learned;
}

BirotorParams Reference() {
  BirotorParams vehicle;
  vehicle.body_mass_kg = 4.0;
  vehicle.tip_mass_kg = 0.28812;
  vehicle.gauge_scale[0] = vehicle.gauge_scale[1] = 1.0;
  return vehicle;
}

LearnedVehicleValues LearnedTipMass(double mass_kg, double sigma_kg) {
  LearnedVehicleValues learned;
  learned.has_tip_mass = true;
  learned.tip_mass_kg = mass_kg;
  learned.tip_mass_std_kg = sigma_kg;
  return learned;
}

TEST(LearnedParameterUpdate, TheStrainScaleMultipliesTheGaugeScale) {
  BirotorParams vehicle = Reference();
  vehicle.gauge_scale[1] = 1.2;  // a file with an identified gauge scale
  std::vector<LearnedChange> changes;
  std::string error;
  ASSERT_TRUE(ApplyLearnedValues(LearnedScales(0.7, 0.9, 0.004), LearnedDeployOptions(), "state", "v.yaml", &vehicle,
                                 &changes, &error))
      << error;
  EXPECT_DOUBLE_EQ(vehicle.gauge_scale[0], 0.7);
  EXPECT_DOUBLE_EQ(vehicle.gauge_scale[1], 1.2 * 0.9);
  EXPECT_EQ(vehicle.body_mass_kg, 4.0);  // not learned: untouched
  ASSERT_EQ(changes.size(), 2u);
  EXPECT_EQ(LearnedChangesText(changes),
            "gauge_scale[0] 1 -> 0.7 (learned 0.7 +- 0.004); gauge_scale[1] 1.2 -> 1.08 (learned 0.9 +- 0.004)");
}

TEST(LearnedParameterUpdate, TheLearnedBodyMassIsWritten) {
  BirotorParams vehicle = Reference();
  LearnedVehicleValues learned;
  learned.has_body_mass = true;
  learned.body_mass_kg = 4.6;
  learned.body_mass_std_kg = 0.03;  // below 0.5 x 0.15 x 4.0 kg = 0.3 kg
  std::vector<LearnedChange> changes;
  std::string error;
  ASSERT_TRUE(ApplyLearnedValues(learned, LearnedDeployOptions(), "state", "v.yaml", &vehicle, &changes, &error));
  EXPECT_EQ(vehicle.body_mass_kg, 4.6);
  EXPECT_EQ(vehicle.gauge_scale[0], 1.0);
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_EQ(changes[0].key, "body_mass_kg");
}

// The tip mass the arm-mode test learned (tip mass +20 % flight: 0.343447 +-
// 0.003168 kg, tests/nodes/estimator_learned_message_test.cc) replaces
// tip_mass_kg; its sigma goes into the change (log line and stamp).
TEST(LearnedParameterUpdate, TheLearnedTipMassIsWritten) {
  BirotorParams vehicle = Reference();
  std::vector<LearnedChange> changes;
  std::string error;
  ASSERT_TRUE(ApplyLearnedValues(LearnedTipMass(0.343447, 0.003168), LearnedDeployOptions(), "state", "v.yaml",
                                 &vehicle, &changes, &error))
      << error;
  EXPECT_EQ(vehicle.tip_mass_kg, 0.343447);
  EXPECT_EQ(vehicle.body_mass_kg, 4.0);
  EXPECT_EQ(vehicle.gauge_scale[0], 1.0);
  EXPECT_EQ(LearnedChangesText(changes), "tip_mass_kg 0.28812 -> 0.343447 (learned 0.343447 +- 0.003168)");
}

// Each refusal leaves the vehicle as it was and names file, key and range.
void ExpectRefused(const LearnedVehicleValues& learned, const std::string& words) {
  BirotorParams vehicle = Reference();
  std::vector<LearnedChange> changes;
  std::string error;
  EXPECT_FALSE(
      ApplyLearnedValues(learned, LearnedDeployOptions(), "run/gauge_state", "v.yaml", &vehicle, &changes, &error));
  EXPECT_NE(error.find(words), std::string::npos) << error;
  EXPECT_EQ(vehicle.gauge_scale[0], 1.0);
  EXPECT_EQ(vehicle.body_mass_kg, 4.0);
  EXPECT_EQ(vehicle.tip_mass_kg, 0.28812);
  EXPECT_TRUE(changes.empty());
}

TEST(LearnedParameterUpdate, RefusesWhatWasNotLearned) {
  // Sigma 0.05 is not below 0.5 x the prior 0.1.
  ExpectRefused(LearnedScales(0.8, 1.0, 0.05),
                "run/gauge_state: strain_scale of arm 1 0.8 +- 0.05 was not learned (sigma not below 0.5 x the prior "
                "sigma 0.1 = 0.05, --learned-max-std-fraction; fly longer in free flight): v.yaml "
                "vehicle.gauge_scale[0] not updated");
  ExpectRefused(LearnedVehicleValues(), "run/gauge_state: holds no learned strain scale, body mass or tip mass");
  LearnedVehicleValues mass;
  mass.has_body_mass = true;
  mass.body_mass_kg = 4.4;
  mass.body_mass_std_kg = 0.3;  // = 0.5 x 0.15 x 4 kg (body_mass_scale_prior_std 0.15)
  ExpectRefused(mass, "v.yaml vehicle.body_mass_kg not updated");
  // The prior's sigma, 0.15 x 0.28812 kg (no reading): not below half of it.
  ExpectRefused(LearnedTipMass(0.28812, 0.043218),
                "run/gauge_state: tip_mass_kg 0.28812 +- 0.043218 was not learned (sigma not below 0.5 x the prior "
                "sigma 0.043218 = 0.021609, --learned-max-std-fraction; fly longer in free flight): v.yaml "
                "vehicle.tip_mass_kg not updated");
}

TEST(LearnedParameterUpdate, RefusesNonFiniteAndOutOfRange) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ExpectRefused(LearnedScales(1.0, nan, 0.01), "strain_scale of arm 2 nan +- 0.01 is not finite");
  ExpectRefused(LearnedScales(1.0, 1.0, nan), "is not finite: v.yaml vehicle.gauge_scale[0] not updated");
  ExpectRefused(LearnedScales(1.0, 1.0, -0.01), "has a negative sigma: v.yaml vehicle.gauge_scale[0] not updated");
  // 1 x 0.4 is below gauge_scale's 0.5 (params/birotor_params_yaml.h).
  ExpectRefused(LearnedScales(0.4, 1.0, 0.01),
                "v.yaml: vehicle.gauge_scale[0] would become 0.4 (1 x learned strain scale 0.4), outside [0.5, 2]: "
                "refused, file not updated");
  LearnedVehicleValues mass;
  mass.has_body_mass = true;
  mass.body_mass_kg = 2000;
  mass.body_mass_std_kg = 0.01;
  ExpectRefused(mass, "v.yaml: vehicle.body_mass_kg would become 2000 (the learned body mass), outside [0.001, 1000]");
  ExpectRefused(LearnedTipMass(nan, 0.003), "run/gauge_state: tip_mass_kg nan +- 0.003 is not finite");
  // 5e-5 kg is below tip_mass_kg's 1e-4 (params/birotor_params_yaml.cc).
  ExpectRefused(LearnedTipMass(5e-5, 1e-6),
                "v.yaml: vehicle.tip_mass_kg would become 5e-05 (the learned tip mass), outside [0.0001, 100]: "
                "refused, file not updated");
}

TEST(LearnedParameterUpdate, TheFractionIsAnOption) {
  LearnedDeployOptions options;
  options.max_std_fraction = 0.9;  // 0.05 < 0.09: accepted now
  BirotorParams vehicle = Reference();
  std::vector<LearnedChange> changes;
  std::string error;
  EXPECT_TRUE(
      ApplyLearnedValues(LearnedScales(0.8, 1.0, 0.05), options, "state", "v.yaml", &vehicle, &changes, &error));
  EXPECT_DOUBLE_EQ(vehicle.gauge_scale[0], 0.8);
}

// The trirotor of config/vehicles/trirotor.yaml: three arms of m_p 0.28812 kg,
// one with another tip mass to show each arm keeps its own.
VehicleDescription Trirotor() {
  VehicleDescription vehicle;
  vehicle.arm_count = 3;
  for (size_t i = 0; i < 3; ++i) vehicle.arms[i].tip_mass_kg = 0.28812;
  vehicle.arms[2].tip_mass_kg = 0.3;
  return vehicle;
}

TEST(LearnedParameterUpdate, TheNArmRatioScalesEveryArmsTipMass) {
  VehicleDescription vehicle = Trirotor();
  const VehicleDescription before = vehicle;
  std::vector<LearnedChange> changes;
  std::string error;
  ASSERT_TRUE(
      ApplyLearnedTipMassRatio(1.09, 0.01, LearnedDeployOptions(), "state", "tri.yaml", &vehicle, &changes, &error))
      << error;
  EXPECT_DOUBLE_EQ(vehicle.arms[0].tip_mass_kg, 1.09 * 0.28812);
  EXPECT_DOUBLE_EQ(vehicle.arms[1].tip_mass_kg, 1.09 * 0.28812);
  EXPECT_DOUBLE_EQ(vehicle.arms[2].tip_mass_kg, 1.09 * 0.3);
  vehicle.arms[0].tip_mass_kg = vehicle.arms[1].tip_mass_kg = 0.28812;
  vehicle.arms[2].tip_mass_kg = 0.3;
  EXPECT_EQ(FirstDifference(vehicle, before), "");  // nothing else changed
  EXPECT_EQ(LearnedChangesText(changes),
            "arms[0].tip_mass_kg 0.28812 -> 0.314051 (learned 1.09 +- 0.01); arms[1].tip_mass_kg 0.28812 -> "
            "0.314051 (learned 1.09 +- 0.01); arms[2].tip_mass_kg 0.3 -> 0.327 (learned 1.09 +- 0.01)");
}

TEST(LearnedParameterUpdate, TheNArmRatioIsRefusedAsTheBirotorsTipMass) {
  VehicleDescription vehicle = Trirotor();
  const VehicleDescription before = vehicle;
  std::vector<LearnedChange> changes;
  std::string error;
  // The prior of r is 0.15 (arm_mode_unconfirmed_tip_mass_std): 0.075 is not below 0.5 x 0.15.
  EXPECT_FALSE(
      ApplyLearnedTipMassRatio(1.09, 0.075, LearnedDeployOptions(), "state", "tri.yaml", &vehicle, &changes, &error));
  EXPECT_EQ(error,
            "state: tip_mass_ratio 1.09 +- 0.075 was not learned (sigma not below 0.5 x the prior sigma 0.15 = 0.075, "
            "--learned-max-std-fraction; fly longer in free flight): tri.yaml vehicle.arms[*].tip_mass_kg not updated");
  LearnedDeployOptions wider;
  wider.max_std_fraction = 0.6;  // 0.09: now learned
  EXPECT_TRUE(ApplyLearnedTipMassRatio(1.09, 0.075, wider, "state", "tri.yaml", &vehicle, &changes, &error)) << error;
  vehicle = before;
  EXPECT_FALSE(ApplyLearnedTipMassRatio(std::numeric_limits<double>::quiet_NaN(), 0.01, LearnedDeployOptions(), "state",
                                        "tri.yaml", &vehicle, &changes, &error));
  EXPECT_NE(error.find("is not finite"), std::string::npos) << error;
  vehicle.arms[2].tip_mass_kg = 99.0;  // 1.09 x 99 leaves [0.0001, 100]
  EXPECT_FALSE(
      ApplyLearnedTipMassRatio(1.09, 0.01, LearnedDeployOptions(), "state", "tri.yaml", &vehicle, &changes, &error));
  EXPECT_EQ(error,
            "tri.yaml: vehicle.arms[2].tip_mass_kg would become 107.91 (99 x learned tip_mass_ratio 1.09), outside "
            "[0.0001, 100]: refused, file not updated");
  EXPECT_EQ(vehicle.arms[0].tip_mass_kg, 0.28812);  // all or nothing
}

}  // namespace
}  // namespace birotor
