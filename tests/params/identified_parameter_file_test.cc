// The identified parameter file loads back as the identified values, and is
// written atomically.
#include "params/identified_parameter_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "identification/deflection_force_map.h"
#include "params/vehicle_params_yaml.h"

namespace birotor {
namespace {

IdentificationResult SampleResult() {
  IdentificationResult r;
  r.ok = true;
  r.mode = "bench";
  r.sources = {"bench.lcm"};
  r.params.arm_stiffness_n_m_rad = 3100.5;
  r.params.thrust_coeff_n_s2_rad2 = 5.01e-5;
  ParameterEstimate k;
  k.key = "arm_stiffness_n_m_rad";
  k.symbol = "k";
  k.value = 3100.5;
  k.sigma = 2.5;
  k.determined = true;
  r.estimates.push_back(k);
  ParameterEstimate d;
  d.key = "arm_damping_n_m_s_rad";
  d.symbol = "d";
  d.value = 0.3;
  d.sigma = 1.0;
  r.estimates.push_back(d);
  r.maps.push_back(FitDeflectionForceMap(0, {-0.001, -0.002, -0.003}, {6.0, 16.0, 26.0}, 1));
  return r;
}

TEST(ParameterFileTest, YamlLoadsBackAsTheIdentifiedValues) {
  const std::string text = IdentifiedParameterYaml(SampleResult());
  const std::string path = ::testing::TempDir() + "/identified_roundtrip.yaml";
  std::ofstream(path) << text;
  const VehicleParams loaded = LoadVehicleParams(path);
  EXPECT_DOUBLE_EQ(loaded.arm_stiffness_n_m_rad, 3100.5);
  EXPECT_DOUBLE_EQ(loaded.thrust_coeff_n_s2_rad2, 5.01e-5);
  EXPECT_NE(text.find("NOT DETERMINED"), std::string::npos);    // d
  EXPECT_NE(text.find("arm 1: force_n ="), std::string::npos);  // the map, as a comment
}

TEST(ParameterFileTest, ReportListsParametersResidualsAndUndetermined) {
  const std::string report = IdentificationReport(SampleResult());
  EXPECT_NE(report.find("| k | arm_stiffness_n_m_rad | 3100.5 | 2.5 |"), std::string::npos) << report;
  EXPECT_NE(report.find("## Undetermined parameters\n\n- d"), std::string::npos) << report;
}

}  // namespace
}  // namespace birotor
