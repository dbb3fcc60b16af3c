// The arm mode shapes and the gauge combinations that read one mode alone:
// the birotor's symmetric mode is b1 - b2 (the arm-mode test's signal), the
// frequencies are OscillatoryModes', and W S = I on the trirotor.
#include "model/multi_arm_modes.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "model/linearization.h"
#include "model/multi_arm_linearization.h"
#include "tests/model/test_vehicles.h"

namespace birotor {
namespace {

using test_vehicles::Birotor;
using test_vehicles::Trirotor;

TEST(MultiArmModeShapes, FrequenciesAreTheOscillatoryModes) {
  for (const VehicleDescription& vehicle : {Birotor(BirotorParams()), Trirotor()}) {
    const std::vector<ArmModeShape> shapes = MultiArmModeShapes(vehicle);
    const std::vector<Mode> modes = OscillatoryModes(LinearizeMultiArmAtHover(vehicle, SolveMultiArmHover(vehicle)).a);
    ASSERT_EQ(shapes.size(), modes.size()) << vehicle.name;
    ASSERT_EQ(static_cast<int>(shapes.size()), vehicle.arm_count) << vehicle.name;
    for (size_t m = 0; m < shapes.size(); ++m) {
      EXPECT_NEAR(shapes[m].frequency_hz, modes[m].frequency_hz, 1e-9) << vehicle.name;
      EXPECT_NEAR(shapes[m].damping_ratio, modes[m].damping_ratio, 1e-9) << vehicle.name;
      EXPECT_NEAR(shapes[m].deflection.cwiseAbs().maxCoeff(), 1.0, 1e-12) << vehicle.name;
    }
  }
}

TEST(MultiArmModeShapes, BirotorSymmetricModeIsTheDifference) {
  // Both arms flap together (arm 1 reads -delta, arm 2 +delta at hover):
  // the lower mode reads b1 - b2, the upper one (the body pitching) b1 + b2.
  const std::vector<ArmModeShape> shapes = MultiArmModeShapes(Birotor(BirotorParams()));
  ASSERT_EQ(shapes.size(), 2u);
  EXPECT_NEAR(shapes[0].frequency_hz, 65.03, 0.01);  // docs/mismatch.md
  EXPECT_NEAR(shapes[0].deflection(0) + shapes[0].deflection(1), 0.0, 1e-9);
  const Eigen::MatrixXd weights = ModalGaugeWeights(shapes, 2);
  ASSERT_EQ(weights.rows(), 2);
  EXPECT_NEAR(weights(0, 0) + weights(0, 1), 0.0, 1e-9);
}

TEST(MultiArmModeShapes, TrirotorWeightsSeparateTheModes) {
  const std::vector<ArmModeShape> shapes = MultiArmModeShapes(Trirotor());
  const Eigen::MatrixXd weights = ModalGaugeWeights(shapes, 3);
  ASSERT_EQ(weights.rows(), 3);
  Eigen::MatrixXd s(3, 3);
  for (int m = 0; m < 3; ++m) s.col(m) = shapes[static_cast<size_t>(m)].deflection;
  EXPECT_LT((weights * s - Eigen::MatrixXd::Identity(3, 3)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(MultiArmModeShapes, TheMostReadableModeIsTheOneTheTurbulenceRings) {
  // Trirotor: the 64.6 Hz mode (arm 1 against arms 2 and 3) rings 19 times
  // the 62.7 Hz one (arms 2 and 3 against each other) in amplitude; the
  // birotor: its symmetric mode, the arm-mode test's.
  const std::vector<ArmModeShape> trirotor = MultiArmModeShapes(Trirotor());
  const int m = MostReadableArmMode(trirotor, ModalGaugeWeights(trirotor, 3));
  EXPECT_EQ(m, 1);
  EXPECT_GT(trirotor[1].turbulence_response, 10.0 * trirotor[0].turbulence_response);
  EXPECT_TRUE(ArmModeStandsAlone(trirotor, m, 0.15, 10.0));
  const std::vector<ArmModeShape> birotor = MultiArmModeShapes(Birotor(BirotorParams()));
  EXPECT_EQ(MostReadableArmMode(birotor, ModalGaugeWeights(birotor, 2)), 0);
  EXPECT_TRUE(ArmModeStandsAlone(birotor, 0, 0.15, 10.0));  // the other mode 23 % higher
  // Two modes 1 % apart that ring alike: neither stands alone.
  std::vector<ArmModeShape> alike(2);
  alike[0].frequency_hz = 60.0;
  alike[1].frequency_hz = 60.6;
  alike[0].turbulence_response = 1.0;
  alike[1].turbulence_response = 0.9;
  EXPECT_FALSE(ArmModeStandsAlone(alike, 0, 0.15, 10.0));
  EXPECT_FALSE(ArmModeStandsAlone(alike, 2, 0.15, 10.0));
}

TEST(MultiArmModeShapes, NoWeightsWithoutAModePerArm) { EXPECT_EQ(ModalGaugeWeights({}, 3).size(), 0); }

// Every arm gauged: the gauged weights are the modal ones.
TEST(MultiArmModeShapes, GaugedWeightsWithEveryGaugeAreTheModalOnes) {
  const std::vector<ArmModeShape> shapes = MultiArmModeShapes(Trirotor());
  const Eigen::MatrixXd all = ModalGaugeWeights(shapes, 3);
  const Eigen::MatrixXd gauged = GaugedModalWeights(shapes, {true, true, true});
  ASSERT_EQ(gauged.rows(), 3);
  EXPECT_LT((gauged - all).cwiseAbs().maxCoeff(), 1e-9);
  for (int m = 0; m < 3; ++m) EXPECT_TRUE(ArmModeLeakSmall(shapes, gauged.row(m), m, 0.15, 10.0)) << m;
}

// The trirotor without arm 2's gauge: each mode read on arms 1 and 3 with
// the nearest other mode nulled; the 64.6 Hz mode is still the one to
// read, and what leaks in of the others within 15 % is small.
TEST(MultiArmModeShapes, TwoGaugesReadAModeWithItsNearestNeighbourNulled) {
  const std::vector<ArmModeShape> shapes = MultiArmModeShapes(Trirotor());
  const Eigen::MatrixXd w = GaugedModalWeights(shapes, {true, false, true});
  ASSERT_EQ(w.rows(), 3);
  for (int m = 0; m < 3; ++m) {
    EXPECT_EQ(w(m, 1), 0.0) << m;
    EXPECT_NEAR(w.row(m).dot(shapes[static_cast<size_t>(m)].deflection), 1.0, 1e-9) << m;
  }
  // 62.7 and 64.6 Hz null each other; 87.8 Hz nulls 64.6 Hz.
  EXPECT_NEAR(w.row(0).dot(shapes[1].deflection), 0.0, 1e-9);
  EXPECT_NEAR(w.row(1).dot(shapes[0].deflection), 0.0, 1e-9);
  EXPECT_NEAR(w.row(2).dot(shapes[1].deflection), 0.0, 1e-9);
  const int pick = MostReadableArmMode(shapes, w);
  EXPECT_EQ(pick, 1);
  EXPECT_TRUE(ArmModeLeakSmall(shapes, w.row(pick), pick, 0.15, 10.0));
  EXPECT_EQ(GaugedModalWeights(shapes, {false, false, false}).size(), 0);
}

}  // namespace
}  // namespace birotor
