// The text of tools/vehicle_analysis_text.h: every table row
// docs/multi-arm-model.md shows is what birotor-analyze --vehicle prints for
// the shipped files (config/vehicles/), and --without-gauge's vehicle.
#include "tools/vehicle_analysis_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

std::string SourceFile(const std::string& relative_path) {
  return std::string(BIROTOR_SOURCE_DIR) + "/" + relative_path;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The cells of a Markdown table row, trimmed; empty for any other line.
std::vector<std::string> Cells(const std::string& line) {
  std::vector<std::string> cells;
  if (line.rfind("| ", 0) != 0) return cells;
  std::stringstream in(line.substr(1));
  std::string cell;
  while (std::getline(in, cell, '|')) {
    const size_t first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
    cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
  }
  return cells;
}

std::vector<std::vector<std::string>> TableRows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream in(text);
  std::string line;
  while (std::getline(in, line))
    if (!Cells(line).empty()) rows.push_back(Cells(line));
  return rows;
}

// Equal cell by cell, except the sigma ratio (last cell of an observability
// row, 3 digits of a scaled SVD) to 2 %.
bool SameRow(const std::vector<std::string>& printed, const std::vector<std::string>& documented) {
  if (printed.size() != documented.size()) return false;
  for (size_t i = 0; i < printed.size(); ++i) {
    if (printed[i] == documented[i]) continue;
    if (printed.size() != 6 || i != 5) return false;
    const double a = std::atof(printed[i].c_str()), b = std::atof(documented[i].c_str());
    if (!(std::abs(a - b) <= 0.02 * std::abs(b))) return false;
  }
  return true;
}

// Every printed row whose first cell starts with `first_cell_prefix` is a row
// of the documentation; returns how many were checked.
int ExpectRowsDocumented(const std::string& printed_text, const std::string& first_cell_prefix) {
  const std::vector<std::vector<std::string>> documented = TableRows(ReadText(SourceFile("docs/multi-arm-model.md")));
  int checked = 0;
  for (const std::vector<std::string>& row : TableRows(printed_text)) {
    if (row[0].rfind(first_cell_prefix, 0) != 0) continue;
    ++checked;
    bool found = false;
    for (const std::vector<std::string>& doc_row : documented) found = found || SameRow(row, doc_row);
    EXPECT_TRUE(found) << "not in docs/multi-arm-model.md: | " << row[0] << " | " << row[1] << " | ...\n"
                       << printed_text;
  }
  return checked;
}

std::string AnalysisText(const VehicleDescription& vehicle) {
  return VehicleAnalysisText(vehicle, AnalyzeVehicle(vehicle));
}

// The tables of "The birotor" and "The trirotor, three gauges": hover, modes
// and observability, every row (headers included).
TEST(VehicleAnalysisText, DocumentedTablesReproduce) {
  for (const char* file : {"config/vehicles/birotor.yaml", "config/vehicles/trirotor.yaml"}) {
    SCOPED_TRACE(file);
    const VehicleDescription vehicle = LoadVehicleDescription(SourceFile(file));
    const int arms = vehicle.arm_count;
    // Three headers, one row per arm in the hover and the modes tables, four sets.
    EXPECT_EQ(ExpectRowsDocumented(AnalysisText(vehicle), ""), 3 + 2 * arms + 4);
  }
  // "The trirotor, two gauges": the gauge rows of each --without-gauge I.
  const VehicleDescription trirotor = LoadVehicleDescription(SourceFile("config/vehicles/trirotor.yaml"));
  for (int missing = 1; missing <= 3; ++missing) {
    SCOPED_TRACE("--without-gauge " + std::to_string(missing));
    VehicleDescription vehicle;
    std::string why;
    ASSERT_TRUE(VehicleWithoutGauges(trirotor, {missing}, &vehicle, &why)) << why;
    EXPECT_EQ(ExpectRowsDocumented(AnalysisText(vehicle), "gauges ("), 2);
  }
  const std::string doc = ReadText(SourceFile("docs/multi-arm-model.md"));
  for (const char* command : {"birotor-analyze --vehicle config/vehicles/birotor.yaml",
                              "birotor-analyze --vehicle config/vehicles/trirotor.yaml",
                              "birotor-analyze --vehicle config/vehicles/trirotor.yaml --without-gauge I"})
    EXPECT_NE(doc.find(command), std::string::npos) << command;
}

TEST(VehicleAnalysisText, TrirotorWithoutArmThreeGauge) {
  const VehicleDescription trirotor = LoadVehicleDescription(SourceFile("config/vehicles/trirotor.yaml"));
  VehicleDescription vehicle;
  std::string why;
  ASSERT_TRUE(VehicleWithoutGauges(trirotor, {3}, &vehicle, &why));
  const std::string text = AnalysisText(vehicle);
  EXPECT_NE(text.find("Vehicle: trirotor, no gauge on arm 3 (3 arms, 2 gauges)"), std::string::npos) << text;
  EXPECT_NE(text.find("| gauges (b1, b2) | 8 / 15 | x, z, phi, x_dot, z_dot, phi_dot | no | [0.21, -0.24, -0.95] |"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("Controllability from the 3 forces: rank 12 / 12"), std::string::npos) << text;
  EXPECT_NE(text.find("| 3 | 45.0 | 45.0 | 0.2500 | no |"), std::string::npos) << text;
}

TEST(VehicleAnalysisText, WithoutGaugesRefusesWhatItCannotRemove) {
  const VehicleDescription trirotor = LoadVehicleDescription(SourceFile("config/vehicles/trirotor.yaml"));
  VehicleDescription vehicle;
  std::string why;
  EXPECT_FALSE(VehicleWithoutGauges(trirotor, {4}, &vehicle, &why));
  EXPECT_EQ(why, "arm 4 is not an arm of trirotor (arms 1 to 3)");
  EXPECT_FALSE(VehicleWithoutGauges(trirotor, {0}, &vehicle, &why));
  EXPECT_EQ(why, "arm 0 is not an arm of trirotor (arms 1 to 3)");
  EXPECT_FALSE(VehicleWithoutGauges(trirotor, {2, 2}, &vehicle, &why));
  EXPECT_EQ(why, "arm 2 is named twice");
  EXPECT_FALSE(VehicleWithoutGauges(trirotor, {1, 2, 3}, &vehicle, &why));
  EXPECT_EQ(why, "no gauge would remain on trirotor (the analysis is of the gauges)");
  ASSERT_TRUE(VehicleWithoutGauges(trirotor, {1, 3}, &vehicle, &why));
  EXPECT_EQ(vehicle.name, "trirotor, no gauge on arms 1, 3");
  EXPECT_EQ(vehicle.GaugeCount(), 1);
  VehicleDescription twice;
  EXPECT_FALSE(VehicleWithoutGauges(vehicle, {1}, &twice, &why));
  EXPECT_EQ(why, "arm 1 of trirotor, no gauge on arms 1, 3 has no gauge to remove");
  ASSERT_TRUE(VehicleWithoutGauges(trirotor, {}, &vehicle, &why));
  EXPECT_EQ(FirstDifference(vehicle, trirotor), "");
  EXPECT_EQ(vehicle.name, "trirotor");
}

TEST(VehicleAnalysisText, DirectionText) {
  EXPECT_EQ(ForceDirectionText(Eigen::Vector3d(0.5774, -0.5774, 0.5774)), "[0.58, -0.58, 0.58]");
  EXPECT_EQ(ForceDirectionText(Eigen::Vector2d(-0.0001, 1.0)), "[-0.00, 1.00]");
}

}  // namespace
}  // namespace birotor
