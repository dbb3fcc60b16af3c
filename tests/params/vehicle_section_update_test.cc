// In-place update of a complete parameter file's vehicle section
// (birotor-identify --update-params): values replaced, everything else kept.
#include "params/vehicle_section_update.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "params/estimator_config_yaml.h"
#include "params/vehicle_params_yaml.h"

namespace birotor {
namespace {

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string WriteTemp(const std::string& text) {
  const std::string path = ::testing::TempDir() + "/vehicle_section_update_" +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".yaml";
  std::ofstream(path) << text;
  return path;
}

TEST(VehicleSectionUpdateTest, ShippedEstimatorFileTakesNewValuesAndKeepsTheRest) {
  const std::string original = ReadText("config/estimator.yaml");
  VehicleParams identified;
  identified.tip_mass_kg = 0.30;
  identified.arm_stiffness_n_m_rad = 3100.5;
  identified.gauge_scale[0] = 1.03;
  identified.gauge_offset_rad[1] = -1.0e-5;
  std::string updated, error;
  ASSERT_TRUE(UpdateVehicleSection(original, identified, "2026-12-01T03:00:00Z by test", &updated, &error)) << error;
  const std::string path = WriteTemp(updated);
  // The whole estimator file still loads, with the identified vehicle and the same estimator options.
  const EstimatorConfig before = LoadEstimatorConfig("config/estimator.yaml");
  const EstimatorConfig after = LoadEstimatorConfig(path);
  EXPECT_EQ(VehicleParamsYaml(after.vehicle), VehicleParamsYaml(identified));
  EXPECT_EQ(after.method, before.method);
  EXPECT_EQ(ReadIdentificationStamp(path), "2026-12-01T03:00:00Z by test");
  // Every comment line of the original is still there; only vehicle lines changed, one stamp line added.
  std::istringstream a(original), b(updated);
  std::string la, lb;
  int original_lines = 0, changed = 0;
  std::vector<std::string> updated_lines;
  while (std::getline(b, lb)) updated_lines.push_back(lb);
  size_t j = 0;
  while (std::getline(a, la)) {
    ++original_lines;
    if (j < updated_lines.size() && updated_lines[j].find("# identified ") != std::string::npos) ++j;
    ASSERT_LT(j, updated_lines.size());
    if (la != updated_lines[j]) {
      ++changed;
      // A changed line keeps its key and its trailing comment.
      EXPECT_EQ(la.substr(0, la.find(':')), updated_lines[j].substr(0, updated_lines[j].find(':')));
      if (la.find('#') != std::string::npos) {
        EXPECT_NE(updated_lines[j].find(la.substr(la.find('#'))), std::string::npos) << updated_lines[j];
      }
    }
    ++j;
  }
  EXPECT_EQ(updated_lines.size(), static_cast<size_t>(original_lines) + 1);
  EXPECT_LE(changed, 16);  // the 14 scalar vehicle keys and the two gauge arrays at most
  // A second update replaces the stamp instead of adding one.
  std::string again;
  ASSERT_TRUE(UpdateVehicleSection(updated, identified, "second", &again, &error)) << error;
  EXPECT_EQ(std::count(again.begin(), again.end(), '\n'), std::count(updated.begin(), updated.end(), '\n'));
  EXPECT_EQ(ReadIdentificationStamp(WriteTemp(again)), "second");
}

TEST(VehicleSectionUpdateTest, IncompleteFileIsRefusedNamingTheKey) {
  std::string updated, error;
  EXPECT_FALSE(UpdateVehicleSection("vehicle:\n  body_mass_kg: 4.0\n", VehicleParams(), "", &updated, &error));
  EXPECT_NE(error.find("tip_mass_kg"), std::string::npos) << error;
  EXPECT_FALSE(UpdateVehicleSection("estimator:\n  method: ekf\n", VehicleParams(), "", &updated, &error));
  EXPECT_NE(error.find("vehicle"), std::string::npos) << error;
}

TEST(VehicleSectionUpdateTest, FileWithoutStampHasNone) {
  EXPECT_EQ(ReadIdentificationStamp("config/reference_vehicle.yaml"), "");
}

}  // namespace
}  // namespace birotor
