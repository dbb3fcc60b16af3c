// The review's log reader: every message counted per channel (also unknown
// channels and messages that do not decode), the shown fields in columns on
// one time axis from the first decoded message, the input stamps kept.
#include "review/flight_data.h"

#include <gtest/gtest.h>

#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_n_t.hpp"
#include "birotor/force_estimate_t.hpp"
#include "birotor/motor_command_n_t.hpp"
#include "birotor/motor_command_t.hpp"
#include "birotor/strain_n_t.hpp"
#include "birotor/strain_t.hpp"
#include "birotor/truth_n_t.hpp"
#include "birotor/truth_t.hpp"
#include "tests/transport/test_files.h"
#include "transport/log_io.h"

namespace birotor {
namespace {

class FlightDataTest : public test_files::TempDirTest {};

TEST_F(FlightDataTest, CountsDecodesAndTimesEveryMessage) {
  const std::string path = Path("flight.lcm");
  LogWriter writer;
  std::string error;
  ASSERT_TRUE(writer.Open(path, &error)) << error;
  const int64_t t0_us = 5'000'000;
  for (int i = 0; i < 100; ++i) {  // 100 ms at 1 kHz
    const int64_t utime = t0_us + 1000 * i;
    strain_t strain{};
    strain.utime = utime;
    ASSERT_TRUE(writer.WriteMessage("BIROTOR_STRAIN", utime, strain));
    force_estimate_t force{};
    force.utime = utime;
    force.force_n[0] = 2.0 + 0.01 * i;
    force.force_std_n[0] = 0.1;
    force.status = i >= 50 ? 1 : 2;  // VALID from 50 ms, CONVERGING before
    ASSERT_TRUE(writer.WriteMessage("BIROTOR_FORCE", utime, force));
    truth_t truth{};
    truth.utime = utime;
    truth.x_m = 0.001 * i;
    ASSERT_TRUE(writer.WriteMessage("BIROTOR_TRUTH", utime, truth));
  }
  estimator_status_t status{};
  status.utime = t0_us + 50'000;
  status.num_inputs = 4;
  status.inputs.resize(4);
  status.inputs[0].nis_mean = 1.9;
  status.inputs[0].fused = 50;
  status.inputs[0].rejected_gate = 2;
  status.inputs[0].rejected_invalid = 1;
  status.accelerometer.nis_mean = 0.7;
  ASSERT_TRUE(writer.WriteMessage("BIROTOR_ESTIMATOR_STATUS", status.utime, status));
  motor_command_t command{};
  command.utime = t0_us + 99'000;
  command.mode = 1;
  command.status = 1;  // FALLBACK_ACTIVE
  ASSERT_TRUE(writer.WriteMessage("BIROTOR_MOTOR_COMMAND", command.utime, command));
  const uint8_t garbage[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  ASSERT_TRUE(writer.Write("BIROTOR_FORCE", t0_us + 99'500, garbage, sizeof(garbage)));     // not a FORCE
  ASSERT_TRUE(writer.Write("BIROTOR_SETPOINT", t0_us + 99'600, garbage, sizeof(garbage)));  // counted only
  ASSERT_TRUE(writer.Close()) << writer.error();

  FlightData data;
  ASSERT_TRUE(ReadFlightData(path, "BIROTOR_", 0.9, &data, &error)) << error;
  EXPECT_EQ(data.events, 304);
  EXPECT_EQ(data.t0_utime, t0_us);
  EXPECT_NEAR(data.duration_s, 0.099, 1e-12);
  EXPECT_EQ(data.channels["BIROTOR_FORCE"].messages, 101);
  EXPECT_EQ(data.channels["BIROTOR_FORCE"].decode_errors, 1);
  EXPECT_EQ(data.channels["BIROTOR_SETPOINT"].messages, 1);
  EXPECT_EQ(data.channels["BIROTOR_STRAIN"].messages, 100);
  ASSERT_EQ(data.force.rows(), 100u);
  EXPECT_DOUBLE_EQ(data.force.columns[0][99], 2.99);  // force 1 of the last sample
  EXPECT_DOUBLE_EQ(data.force.columns[2][0], 0.1);    // its sigma
  EXPECT_NEAR(data.force.t_s[99], 0.099, 1e-12);
  ASSERT_EQ(data.truth.rows(), 100u);
  EXPECT_DOUBLE_EQ(data.truth.columns[4][10], 0.01);  // true x
  ASSERT_EQ(data.status.rows(), 1u);
  EXPECT_DOUBLE_EQ(data.status.columns[0][0], 1.9);                  // STRAIN NIS mean
  EXPECT_DOUBLE_EQ(data.status.columns[4][0], 0.7);                  // accelerometer NIS mean
  EXPECT_DOUBLE_EQ(data.status.columns[kReviewInputs][0], 50.0);     // STRAIN fused
  EXPECT_DOUBLE_EQ(data.status.columns[2 * kReviewInputs][0], 3.0);  // STRAIN gated + invalid
  ASSERT_EQ(data.motor_command.rows(), 1u);
  EXPECT_DOUBLE_EQ(data.motor_command.columns[3][0], 1.0);
  ASSERT_EQ(data.input_t_s[0].size(), 100u);  // STRAIN stamps
  EXPECT_NEAR(data.input_t_s[0][1], 0.001, 1e-12);
  EXPECT_TRUE(data.input_t_s[1].empty());  // no MOTOR
}

// A birotor FORCE's rotor-fault bits move to the rotor-fault column, as
// ToCountedMessage moves them (one layout for every vehicle).
TEST_F(FlightDataTest, BirotorRotorFaultBitsGoToTheRotorFaultColumn) {
  const std::string path = Path("fault.lcm");
  LogWriter writer;
  std::string error;
  ASSERT_TRUE(writer.Open(path, &error)) << error;
  force_estimate_t force{};
  force.utime = 1'000'000;
  force.status = kStatusValid | kStatusRotor2Fault;
  ASSERT_TRUE(writer.WriteMessage("BIROTOR_FORCE", force.utime, force));
  ASSERT_TRUE(writer.Close()) << writer.error();
  FlightData data;
  ASSERT_TRUE(ReadFlightData(path, "BIROTOR_", 0.9, &data, &error)) << error;
  ASSERT_EQ(data.force.rows(), 1u);
  EXPECT_EQ(data.rotor_count, 2);
  EXPECT_DOUBLE_EQ(data.force.columns[data.ForceStatusColumn()][0], double(kStatusValid));
  EXPECT_DOUBLE_EQ(data.force.columns[data.ForceFaultColumn()][0], 2.0);  // bit 1: rotor 2
  std::vector<std::string> words;
  for (const ForceFlag& flag : ForceFlags(data)) words.push_back(flag.word);
  EXPECT_EQ(words, (std::vector<std::string>{"VALID", "CONVERGING", "REJECTED", "STALE", "ROTOR1_FAULT", "ROTOR2_FAULT",
                                             "RESET", "NO_MOTOR", "THRUST_DEFICIT", "CONFLICT", "MODEL_MISMATCH"}));
}

// A three-rotor log (the counted types on the _N channels): the tables take
// three rotors from the first counted message; a message of another count
// (a quadrotor's in the same log) is dropped and counted.
TEST_F(FlightDataTest, ReadsTheCountedTypesOfAThreeRotorVehicle) {
  const std::string path = Path("trirotor.lcm");
  LogWriter writer;
  std::string error;
  ASSERT_TRUE(writer.Open(path, &error)) << error;
  for (int i = 0; i < 10; ++i) {
    const int64_t utime = 2'000'000 + 1000 * i;
    strain_n_t strain{};
    strain.utime = utime;
    strain.n_arms = 3;
    strain.deflection_rad = {0.001, 0.002, 0.003};
    ASSERT_TRUE(writer.WriteMessage("BIROTOR_STRAIN_N", utime, strain));
    force_estimate_n_t force{};
    force.utime = utime;
    force.n_rotors = 3;
    force.force_n = {27.0, 14.0, 14.0 + i};
    force.force_std_n = {0.1, 0.1, 0.2};
    force.thrust_scale = {1.0, 1.0, 0.75};
    force.status = kStatusValid;
    force.rotor_fault_bits = i >= 5 ? 4 : 0;  // rotor 3 from 5 ms
    ASSERT_TRUE(writer.WriteMessage("BIROTOR_FORCE_N", utime, force));
    truth_n_t truth{};
    truth.utime = utime;
    truth.n_arms = 3;
    truth.x_m = 0.5;
    truth.z_m = 1.0;
    truth.phi_rad = 0.01 * i;
    truth.deflection_rad = truth.deflection_dot_rad_s = {0, 0, 0};
    truth.omega_rad_s = {770, 560, 560};
    truth.force_n = {27.5, 14.3, 14.3};
    truth.thrust_scale = {1.0, 1.0, 0.75};
    ASSERT_TRUE(writer.WriteMessage("BIROTOR_TRUTH_N", utime, truth));
    motor_command_n_t command{};
    command.utime = utime;
    command.n_rotors = 3;
    command.omega_cmd_rad_s = {770, 560, 561};
    command.mode = 1;
    ASSERT_TRUE(writer.WriteMessage("BIROTOR_MOTOR_COMMAND_N", utime, command));
  }
  force_estimate_n_t quad{};
  quad.utime = 2'010'000;
  quad.n_rotors = 4;
  quad.force_n = quad.force_std_n = quad.thrust_scale = {1, 1, 1, 1};
  ASSERT_TRUE(writer.WriteMessage("BIROTOR_FORCE_N", quad.utime, quad));
  ASSERT_TRUE(writer.Close()) << writer.error();

  FlightData data;
  ASSERT_TRUE(ReadFlightData(path, "BIROTOR_", 0.9, &data, &error)) << error;
  EXPECT_EQ(data.rotor_count, 3);
  EXPECT_EQ(data.count_mismatches, 1);
  EXPECT_EQ(data.channels["BIROTOR_FORCE_N"].decode_errors, 1);
  ASSERT_EQ(data.force.rows(), 10u);
  ASSERT_EQ(data.force.labels.size(), 11u);  // 3 forces, 3 sigmas, 3 scales, status, rotor faults
  EXPECT_EQ(data.force.labels[2], "force 3 [N]");
  EXPECT_DOUBLE_EQ(data.force.columns[data.ForceColumn(2)][9], 23.0);
  EXPECT_DOUBLE_EQ(data.force.columns[data.ForceSigmaColumn(2)][0], 0.2);
  EXPECT_DOUBLE_EQ(data.force.columns[data.ForceScaleColumn(2)][0], 0.75);
  EXPECT_DOUBLE_EQ(data.force.columns[data.ForceFaultColumn()][5], 4.0);
  ASSERT_EQ(data.truth.rows(), 10u);
  EXPECT_DOUBLE_EQ(data.truth.columns[data.TruthForceColumn(0)][0], 27.5);
  EXPECT_DOUBLE_EQ(data.truth.columns[data.TruthXColumn()][0], 0.5);
  EXPECT_DOUBLE_EQ(data.truth.columns[data.TruthPhiColumn()][9], 0.09);
  ASSERT_EQ(data.motor_command.rows(), 10u);
  EXPECT_DOUBLE_EQ(data.motor_command.columns[data.CommandColumn(2)][0], 561.0);
  EXPECT_DOUBLE_EQ(data.motor_command.columns[data.CommandModeColumn()][0], 1.0);
  EXPECT_EQ(data.input_t_s[0].size(), 10u);  // STRAIN_N stamps
  const std::vector<ForceFlag> flags = ForceFlags(data);
  ASSERT_EQ(flags.size(), 12u);  // ROTOR1..3_FAULT in place of the birotor's two
  EXPECT_EQ(flags[6].word, "ROTOR3_FAULT");
  EXPECT_EQ(flags[6].column, data.ForceFaultColumn());
  EXPECT_EQ(flags[6].bit, 4);
}

TEST_F(FlightDataTest, MissingAndEmptyLogsAreErrorsNamingTheFile) {
  FlightData data;
  std::string error;
  EXPECT_FALSE(ReadFlightData(Path("missing.lcm"), "BIROTOR_", 0.9, &data, &error));
  EXPECT_NE(error.find("missing.lcm"), std::string::npos) << error;
  test_files::WriteBytes(Path("empty.lcm"), {});
  EXPECT_FALSE(ReadFlightData(Path("empty.lcm"), "BIROTOR_", 0.9, &data, &error));
  EXPECT_NE(error.find("empty.lcm"), std::string::npos) << error;
}

}  // namespace
}  // namespace birotor
