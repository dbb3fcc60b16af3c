// The review's log reader: every message counted per channel (also unknown
// channels and messages that do not decode), the shown fields in columns on
// one time axis from the first decoded message, the input stamps kept.
#include "review/flight_data.h"

#include <gtest/gtest.h>

#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_t.hpp"
#include "birotor/motor_command_t.hpp"
#include "birotor/strain_t.hpp"
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
