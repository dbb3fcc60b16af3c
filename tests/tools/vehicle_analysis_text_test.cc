// The text of tools/vehicle_analysis_text.h: the rows of the table in
// docs/multi-arm-model.md for the test trirotor with two gauges.
#include "tools/vehicle_analysis_text.h"

#include <gtest/gtest.h>

#include "tests/model/test_vehicles.h"

namespace birotor {
namespace {

TEST(VehicleAnalysisText, TrirotorTwoGaugesTable) {
  const VehicleDescription vehicle = test_vehicles::Trirotor(false);
  const std::string text = VehicleAnalysisText(vehicle, AnalyzeVehicle(vehicle));
  EXPECT_NE(text.find("Vehicle: trirotor, no gauge on arm 3 (3 arms, 2 gauges)"), std::string::npos) << text;
  EXPECT_NE(text.find("| gauges (b1, b2) | 8 / 15 | x, z, phi, x_dot, z_dot, phi_dot | no | [0.12, -0.21, -0.97] |"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("| gauges (b1, b2) + IMU (gyro, accelerometer) | 10 / 15 | x, z, phi, x_dot, z_dot | yes | - |"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("Controllability from the 3 forces: rank 12 / 12"), std::string::npos) << text;
  EXPECT_NE(text.find("| 3 | 90.0 | 40.0 | 0.1607 | no |"), std::string::npos) << text;
}

TEST(VehicleAnalysisText, DirectionText) {
  EXPECT_EQ(ForceDirectionText(Eigen::Vector3d(0.5774, -0.5774, 0.5774)), "[0.58, -0.58, 0.58]");
  EXPECT_EQ(ForceDirectionText(Eigen::Vector2d(-0.0001, 1.0)), "[-0.00, 1.00]");
}

}  // namespace
}  // namespace birotor
