// Vehicle description files: both forms load, the shipped vehicles are what
// docs/vehicle-description.md says, bad and implausible input is refused
// naming the file, the key and the allowed range.
#include "params/vehicle_description_yaml.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "model/vehicle_description_checksum.h"
#include "params/birotor_params_yaml.h"
#include "params/controller_config_yaml.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "tests/params/param_error_of.h"
#include "tests/params/temp_file.h"

namespace birotor {
namespace {

using ::birotor::testing::ParamErrorOf;

std::string WriteTemp(const std::string& text) { return testing::WriteTempFile("vehicle_description_", text); }
std::string ReadText(const std::string& path) { return testing::ReadTextFile(path); }

// The text of config/vehicles/birotor.yaml with from replaced by to (once).
std::string BirotorWith(const std::string& from, const std::string& to) {
  std::string text = ReadText("config/vehicles/birotor.yaml");
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The file text is refused with a message naming the file and each part.
void ExpectRefused(const std::string& text, const std::vector<std::string>& parts) {
  const std::string path = WriteTemp(text);
  const std::string message = ParamErrorOf([&] { LoadVehicleDescription(path); });
  ASSERT_FALSE(message.empty()) << "accepted:\n" << text;
  EXPECT_NE(message.find(path), std::string::npos) << message;
  for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << part << "\n" << message;
}

TEST(VehicleDescriptionYaml, BothBirotorFilesGiveTheReferenceDescription) {
  const VehicleDescription reference = BirotorDescription(LoadBirotorParams("config/reference_vehicle.yaml"));
  EXPECT_EQ(FirstDifference(LoadVehicleDescription("config/vehicles/birotor.yaml"), reference), "");
  EXPECT_EQ(FirstDifference(LoadVehicleDescription("config/reference_vehicle.yaml"), reference), "");
  BirotorParams params;
  std::string why;
  ASSERT_TRUE(ToBirotorParams(LoadVehicleDescription("config/vehicles/birotor.yaml"), &params, &why)) << why;
  EXPECT_DOUBLE_EQ(params.arm_stiffness_n_m_rad, 2628.0);  // config/reference_vehicle.yaml
}

// The figures of docs/vehicle-description.md, "The trirotor". Hover, A f =
// [0, W, tau_g] with W = g (m + 3 m_p) = 47.71937 N and the tip weights'
// moment tau_g = m_p g L (cos 180 + 2 cos 45 deg) = 0.292689 N m: the F_x row
// gives f_2 = f_3 = f, the torque row L (2 f - f_1) = tau_g, so
// f_1 = 2 f - m_p g (sqrt 2 - 1), and F_z f_1 + sqrt(2) f = W:
// f = (W + m_p g (sqrt 2 - 1)) / (2 + sqrt 2) = 14.31959 N, f_1 = 27.46842 N.
TEST(VehicleDescriptionYaml, TrirotorLoadsWithTheDocumentedFigures) {
  const VehicleDescription d = LoadVehicleDescription("config/vehicles/trirotor.yaml");
  ASSERT_EQ(d.arm_count, 3);
  EXPECT_EQ(d.GaugeCount(), 3);
  for (size_t i = 0; i < 3; ++i) EXPECT_NEAR(std::fabs(d.arms[i].ThrustLeverM()), 0.25, 1e-12) << i;
  const AllocationMargin margin = ControlledAxesMargin(d);
  ASSERT_EQ(margin.rows, 3);
  EXPECT_NEAR(margin.singular_values(0), 1.77462, 1e-5);
  EXPECT_NEAR(margin.singular_values(1), 1.36041, 1e-5);
  EXPECT_NEAR(margin.singular_values(2), 1.0, 1e-9);
  EXPECT_NEAR(margin.ratio, 0.56350, 1e-5);
  const double weight_n = 9.81 * (4.0 + 3 * 0.28812), tip_n = 0.28812 * 9.81 * (std::sqrt(2.0) - 1.0);
  const Eigen::Vector3d hover_wrench = HoverWrench(d);
  EXPECT_NEAR(hover_wrench(kWrenchFx), 0.0, 1e-12);
  EXPECT_NEAR(hover_wrench(kWrenchFz), weight_n, 1e-12);
  EXPECT_NEAR(hover_wrench(kWrenchTorque), 0.25 * tip_n, 1e-12);
  EXPECT_NEAR(hover_wrench(kWrenchTorque), 0.292689, 1e-6);
  const HoverSolution hover = SolveHover(d);
  const double f_n = (weight_n + tip_n) / (2.0 + std::sqrt(2.0));
  EXPECT_NEAR(f_n, 14.31959, 1e-5);
  EXPECT_NEAR(hover.thrust_n[0], 2.0 * f_n - tip_n, 1e-9);
  EXPECT_NEAR(hover.thrust_n[0], 27.46842, 1e-5);
  EXPECT_NEAR(hover.thrust_n[1], f_n, 1e-9);
  EXPECT_NEAR(hover.thrust_n[2], f_n, 1e-9);
  // sqrt(f / c_T), c_T = 4.6e-5; of omega_max 1200 rad/s.
  EXPECT_NEAR(hover.omega_rad_s[0], 772.75, 0.01);  // 64.4 %
  EXPECT_NEAR(hover.omega_rad_s[1], 557.94, 0.01);  // 46.5 %
  EXPECT_NEAR(hover.omega_rad_s[2], 557.94, 0.01);
  // Maximum lift: straight up at acceleration a without turning, every mass
  // needs (g + a) / g of its weight, so A f = (1 + a / g) [0, W, tau_g] and
  // f = (1 + a / g) f_hover. Rotor 1 reaches 0.95 omega_max first, at
  // c_T (1140 rad/s)^2 = 59.7816 N: lift = W 59.7816 / f_1 = 103.855 N,
  // 2.176 W (rotors 2 and 3 then at 31.17 N).
  const double ceiling_n = 4.6e-5 * 1140.0 * 1140.0;
  const double lift_scale = ceiling_n / hover.thrust_n[0];
  EXPECT_NEAR(lift_scale * weight_n, 103.855, 1e-3);
  EXPECT_NEAR(lift_scale, 2.176, 1e-3);
  EXPECT_LT(lift_scale * hover.thrust_n[1], ceiling_n);
  // Lateral force at zero tilt: A f = [F_x, W, tau_g]. The F_z and torque rows
  // keep f_1 and f_2 + f_3 = 2 f, F_x = (f_2 - f_3) sin 45 deg; the floor
  // 0.1 omega_max on rotor 3 bounds it at sqrt(2) (f - c_T (120 rad/s)^2) =
  // 19.314 N, 0.405 g (the tip masses' inertial moment m_p a_x L sum sin
  // alpha_i is 0), rotor 2 then at 2 f - c_T 120^2 = 27.977 N, 779.87 rad/s.
  const AllocationMatrix a = WrenchAllocation(d);
  const double floor_n = 4.6e-5 * 120.0 * 120.0;
  const double lateral_n = std::sqrt(2.0) * (f_n - floor_n);
  EXPECT_NEAR(lateral_n, 19.314, 1e-3);
  EXPECT_NEAR(lateral_n / weight_n, 0.405, 1e-3);
  const double f2 = f_n + lateral_n / std::sqrt(2.0), f3 = floor_n;
  const Eigen::Vector3d lateral_thrust(hover.thrust_n[0], f2, f3);
  const Eigen::Vector3d wrench = a * lateral_thrust;
  EXPECT_NEAR(wrench(kWrenchFx), lateral_n, 1e-9);
  EXPECT_NEAR(wrench(kWrenchFz), hover_wrench(kWrenchFz), 1e-9);
  EXPECT_NEAR(wrench(kWrenchTorque), hover_wrench(kWrenchTorque), 1e-9);
  EXPECT_NEAR(std::sqrt(f2 / 4.6e-5), 779.87, 0.01);
  EXPECT_LT(f2, ceiling_n);
}

// The plausibility check at load time refuses none of the shipped vehicles:
// the reference, estimator and controller files, every scenario's flown
// vehicle (payload +-15 %, stiffness +-20 %, c_T +-20 %, ...) and both
// files of config/vehicles/.
TEST(VehicleDescriptionYaml, EveryShippedVehicleLoads) {
  int files = 0;
  for (const std::string dir : {"config", "config/scenarios", "config/vehicles"}) {
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      const std::string path = entry.path().string();
      if (entry.path().extension() != ".yaml" || ReadText(path).find("\nvehicle:") == std::string::npos) continue;
      EXPECT_EQ(ParamErrorOf([&] { LoadVehicleDescription(path); }), "") << path;
      if (dir == "config/scenarios") {
        EXPECT_EQ(ParamErrorOf([&] { LoadScenario(path); }), "") << path;
      }
      ++files;
    }
  }
  EXPECT_EQ(ParamErrorOf([] { LoadEstimatorConfig("config/estimator.yaml"); }), "");
  EXPECT_EQ(ParamErrorOf([] { LoadControllerConfig("config/controller.yaml"); }), "");
  EXPECT_GE(files, 33);  // 3 in config/, 28 scenarios, 2 vehicles
}

TEST(VehicleDescriptionYaml, TooHeavyIsRefusedInBothForms) {
  // 9.81 (400 + 2 x 0.28812) / 2 = 1964.83 N per rotor: 6535.57 rad/s > 1200.
  const std::vector<std::string> parts = {"key 'vehicle': the vehicle cannot fly",
                                          "speed 6535.57 rad/s above omega_max_rad_s 1200",
                                          "(allowed: hover speed <= omega_max_rad_s)"};
  ExpectRefused(BirotorWith("body_mass_kg: 4.0", "body_mass_kg: 400"), parts);
  std::string old_form = ReadText("config/reference_vehicle.yaml");
  old_form.replace(old_form.find("body_mass_kg: 4.0"), 17, "body_mass_kg: 400");
  const std::string path = WriteTemp(old_form);
  const std::string message = ParamErrorOf([&] { LoadBirotorParams(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
}

TEST(VehicleDescriptionYaml, ArmCountOutsideTwoToSix) {
  const std::string text = ReadText("config/vehicles/birotor.yaml");
  const size_t arms = text.find("    - angle_deg: 180");
  const std::string arm = text.substr(arms, text.find("    - angle_deg: 0 ") - arms);
  std::string seven = text;
  for (int i = 0; i < 5; ++i) seven += arm;
  ExpectRefused(seven, {"key 'vehicle.arms': a list of 7 arms", "(allowed: [2, 6] arms, each a map)"});
  ExpectRefused(text.substr(0, arms) + arm, {"key 'vehicle.arms': a list of 1 arms", "(allowed: [2, 6] arms"});
}

TEST(VehicleDescriptionYaml, MissingArmKeyIsNamed) {
  ExpectRefused(BirotorWith("      damping_n_m_s_rad: 0.25    # d\n", ""),
                {"missing key: vehicle.arms[0].damping_n_m_s_rad"});
  ExpectRefused(BirotorWith("    - angle_deg: 0               # arm 2 along body +x; lever +0.25 m\n"
                            "      thrust_angle_deg: 0\n",
                            "    - thrust_angle_deg: 0\n"),
                {"missing key: vehicle.arms[1].angle_rad"});
}

TEST(VehicleDescriptionYaml, NanAndOutOfRangeNameKeyAndRange) {
  ExpectRefused(BirotorWith("tip_mass_kg: 0.28812 ", "tip_mass_kg: .nan "),
                {"key 'vehicle.arms[0].tip_mass_kg': value nan is out of range", "(allowed: [0.0001, 100])"});
  ExpectRefused(BirotorWith("      length_m: 0.25\n      spin: -1", "      length_m: 12\n      spin: -1"),
                {"key 'vehicle.arms[1].length_m': value 12 is out of range", "(allowed: [0.001, 10])"});
  ExpectRefused(BirotorWith("spin: -1", "spin: 0"), {"key 'vehicle.arms[1].spin'", "(allowed: 1 or -1)"});
}

TEST(VehicleDescriptionYaml, BothFormsInOneFileAreRefused) {
  ExpectRefused(
      BirotorWith("  arms:\n", "  arm_length_m: 0.25\n  arms:\n"),
      {"key 'vehicle': holds both the N-arm form (vehicle.arms) and the birotor form (vehicle.arm_length_m)"});
}

TEST(VehicleDescriptionYaml, UnknownArmKeyIsRefused) {
  ExpectRefused(BirotorWith("      has_gauge: true\n", "      has_gauge: true\n      has_gage: true\n"),
                {"key 'vehicle.arms[0].has_gage': unknown key; did you mean 'has_gauge'?"});
  ExpectRefused(BirotorWith("thrust_angle_deg: 0        # thrust", "thrust_angle_deg: 0\n      thrust_angle_rad: 0 #"),
                {"key 'vehicle.arms[0].thrust_angle_deg': given with thrust_angle_rad",
                 "(allowed: thrust_angle_rad in [-6.28319, 6.28319] or thrust_angle_deg in [-360, 360])"});
}

TEST(VehicleDescriptionYaml, GaugeOnAnArmWithoutLeverIsRefused) {
  // Arm 2 along +x with its thrust along the arm (theta = -90 deg): l_2 = 0.
  // The allocation loses the torque axis too (both reported).
  ExpectRefused(BirotorWith("    - angle_deg: 0               # arm 2 along body +x; lever +0.25 m\n"
                            "      thrust_angle_deg: 0\n",
                            "    - angle_deg: 0\n      thrust_angle_deg: -90\n"),
                {"key 'vehicle': the vehicle cannot fly", "arms[1].has_gauge: true on an arm whose thrust lever",
                 "(allowed: |l| >= 0.1 x length_m, or has_gauge false)"});
}

// The description checksum of VEHICLE_DESCRIPTION (model/vehicle_description_checksum.h)
// for the shipped files: the birotor's is the reference birotor's of
// tests/model/vehicle_description_checksum_test.cc, bit for bit (180 deg
// reads as exactly pi), and one changed key changes it.
TEST(VehicleDescriptionYaml, ChecksumOfTheShippedFiles) {
  const std::string birotor = DescriptionChecksum(LoadVehicleDescription("config/vehicles/birotor.yaml"));
  EXPECT_EQ(birotor, "3c46c6d41f8659af");
  EXPECT_EQ(DescriptionChecksum(LoadVehicleDescription("config/reference_vehicle.yaml")), birotor);
  EXPECT_EQ(DescriptionChecksum(LoadVehicleDescription("config/vehicles/trirotor.yaml")), "39efb21ecd444d4f");
  const std::string path = WriteTemp(BirotorWith("tip_mass_kg: 0.28812", "tip_mass_kg: 0.28813"));
  EXPECT_NE(DescriptionChecksum(LoadVehicleDescription(path)), birotor);
}

}  // namespace
}  // namespace birotor
