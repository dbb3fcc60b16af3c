// birotor-identify --vehicle (issue 38 item 2) as a process: the bench log of
// the modified trirotor (tests/data/trirotor_modified.yaml) written by
// birotor-sim --vehicle (20 s of config/scenarios/bench.yaml, shortened from
// 120 s), identified against config/vehicles/trirotor.yaml, and the refusal
// of the same log against the birotor's description (2 arms); then a 20 s
// flight_id of the same vehicle identified in flight mode against the
// bench's description (its m_p and d held, 12 windows: a shortened
// config/identification.yaml), a flight log refused in bench mode and the
// bench and flight logs refused together.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

namespace fs = std::filesystem;

std::string SourcePath(const std::string& relative) { return std::string(BIROTOR_SOURCE_DIR) + "/" + relative; }

// The program with args, stderr to a file; its exit status.
int RunProgram(const std::string& program, const std::vector<std::string>& args) {
  std::string command = program + " --log-level warn";
  for (const std::string& a : args) command += " '" + a + "'";
  command += " 2> /dev/null";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct Folder {
  Folder() {
    char pattern[] = "/tmp/multi_arm_identify_XXXXXX";
    path = mkdtemp(pattern);
  }
  ~Folder() { fs::remove_all(path); }
  std::string path;
};

TEST(MultiArmIdentifyTest, WritesTheModifiedTrirotorAndRefusesAnotherCount) {
  const Folder folder;
  const std::string log = folder.path + "/bench3.lcm", out = folder.path + "/identified.yaml";
  const std::string truth_file = SourcePath("tests/data/trirotor_modified.yaml");
  ASSERT_EQ(RunProgram(BIROTOR_SIM_BIN, {"--vehicle", truth_file, "--scenario", "bench", "--set",
                                         "scenario.duration_s=20", "--output", log}),
            0);
  ASSERT_EQ(RunProgram(BIROTOR_IDENTIFY_BIN,
                       {"--vehicle", SourcePath("config/vehicles/trirotor.yaml"), "--log", log, "--output", out}),
            0);
  const VehicleDescription truth = LoadVehicleDescription(truth_file);
  const VehicleDescription identified = LoadVehicleDescription(out);
  ASSERT_EQ(identified.arm_count, 3);
  for (size_t i = 0; i < 3; ++i) {
    const ArmDescription &t = truth.arms[i], &e = identified.arms[i];
    // Issue 38's targets: 1 % (tip mass 2 %, damping 5 %).
    EXPECT_NEAR(e.stiffness_n_m_rad, t.stiffness_n_m_rad, 0.01 * t.stiffness_n_m_rad) << "arm " << i + 1;
    EXPECT_NEAR(e.damping_n_m_s_rad, t.damping_n_m_s_rad, 0.05 * t.damping_n_m_s_rad) << "arm " << i + 1;
    EXPECT_NEAR(e.tip_mass_kg, t.tip_mass_kg, 0.02 * t.tip_mass_kg) << "arm " << i + 1;
    EXPECT_NEAR(e.thrust_coeff_n_s2_rad2, t.thrust_coeff_n_s2_rad2, 0.01 * t.thrust_coeff_n_s2_rad2);
    EXPECT_NEAR(e.motor_time_constant_s, t.motor_time_constant_s, 0.01 * t.motor_time_constant_s);
  }
  // The same log against the birotor: exit 1, nothing written.
  const std::string refused = folder.path + "/refused.yaml";
  EXPECT_EQ(RunProgram(BIROTOR_IDENTIFY_BIN,
                       {"--vehicle", SourcePath("config/reference_vehicle.yaml"), "--log", log, "--output", refused}),
            1);
  EXPECT_FALSE(fs::exists(refused));

  // Flight after the bench: the identified description is the base.
  const std::string flight = folder.path + "/flight3.lcm", flown = folder.path + "/flown.yaml";
  ASSERT_EQ(RunProgram(BIROTOR_SIM_BIN, {"--vehicle", truth_file, "--scenario", "flight_id", "--set",
                                         "scenario.duration_s=20", "--output", flight}),
            0);
  std::ifstream in(SourcePath("config/identification.yaml"));
  std::stringstream text;
  text << in.rdbuf();
  std::string options = text.str();
  const size_t key = options.find("flight_max_windows:");
  ASSERT_NE(key, std::string::npos);
  options.replace(key, options.find('\n', key) - key, "flight_max_windows: 12");
  const std::string config = folder.path + "/identification.yaml";
  std::ofstream(config) << options;
  ASSERT_EQ(RunProgram(BIROTOR_IDENTIFY_BIN,
                       {"--vehicle", out, "--mode", "flight", "--config", config, "--log", flight, "--output", flown}),
            0);
  const VehicleDescription after_flight = LoadVehicleDescription(flown);
  for (size_t i = 0; i < 3; ++i) {
    const ArmDescription &t = truth.arms[i], &e = after_flight.arms[i];
    std::printf("flight arm %zu: k %+.3f %%, c_T %+.3f %%, tau_m %+.3f %%\n", i + 1,
                100.0 * (e.stiffness_n_m_rad / t.stiffness_n_m_rad - 1.0),
                100.0 * (e.thrust_coeff_n_s2_rad2 / t.thrust_coeff_n_s2_rad2 - 1.0),
                100.0 * (e.motor_time_constant_s / t.motor_time_constant_s - 1.0));
    // Measured (this test): worst k -0.065 % (arm 1), c_T -0.151 % (arm 2),
    // tau_m -0.472 % (arm 1); the bounds are 1.5 x those (issue 38: 1 %).
    EXPECT_NEAR(e.stiffness_n_m_rad, t.stiffness_n_m_rad, 0.001 * t.stiffness_n_m_rad) << "arm " << i + 1;
    EXPECT_NEAR(e.thrust_coeff_n_s2_rad2, t.thrust_coeff_n_s2_rad2, 0.0023 * t.thrust_coeff_n_s2_rad2);
    EXPECT_NEAR(e.motor_time_constant_s, t.motor_time_constant_s, 0.0071 * t.motor_time_constant_s);
    // Held in flight: the bench's values stand.
    EXPECT_EQ(e.tip_mass_kg, identified.arms[i].tip_mass_kg);
    EXPECT_EQ(e.damping_n_m_s_rad, identified.arms[i].damping_n_m_s_rad);
  }
  // The flight log in bench mode: no load cells, refused, nothing written.
  const std::string no_cells = folder.path + "/no_cells.yaml";
  EXPECT_EQ(RunProgram(BIROTOR_IDENTIFY_BIN, {"--vehicle", SourcePath("config/vehicles/trirotor.yaml"), "--mode",
                                              "bench", "--log", flight, "--output", no_cells}),
            1);
  EXPECT_FALSE(fs::exists(no_cells));
  // Bench and flight logs together (auto): not joined for N arms, refused.
  EXPECT_EQ(RunProgram(BIROTOR_IDENTIFY_BIN, {"--vehicle", SourcePath("config/vehicles/trirotor.yaml"), "--log", log,
                                              "--log", flight, "--output", no_cells}),
            1);
  EXPECT_FALSE(fs::exists(no_cells));
}

}  // namespace
}  // namespace birotor
