// Tests of transport/message_conversion.h: every field survives
// message -> sample -> message, and the status bits match the .lcm constants.
#include "transport/message_conversion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/transport/test_messages.h"
#include "transport/lcm_codec.h"

namespace birotor {
namespace {

using transport_test::Encode;
using transport_test::MakeTestMessage;

template <class Msg>
class ConversionTest : public ::testing::Test {};

using ConvertedMessages =
    ::testing::Types<strain_t, motor_t, imu_t, pose_t, loadcell_t, truth_t, force_estimate_t, motor_command_t>;
TYPED_TEST_SUITE(ConversionTest, ConvertedMessages);

TYPED_TEST(ConversionTest, MessageSampleMessageKeepsEveryField) {
  const TypeParam original = MakeTestMessage<TypeParam>();
  const TypeParam converted = ToMessage(FromMessage(original));
  EXPECT_EQ(Encode(converted), Encode(original));  // bytewise, NaN included
}

TEST(ConversionTest, StrainFieldsMapByName) {
  const StrainSample sample = FromMessage(MakeTestMessage<strain_t>());
  EXPECT_EQ(sample.utime, 1234567);
  EXPECT_EQ(sample.seq, 42);
  EXPECT_EQ(sample.deflection_rad[0], -0.0123);
  EXPECT_EQ(sample.deflection_rad[1], 0.0125);
}

TEST(ConversionTest, MotorKeepsMissingTelemetryAsNan) {
  const MotorSample sample = FromMessage(MakeTestMessage<motor_t>());
  EXPECT_EQ(sample.seq, -7);
  EXPECT_EQ(sample.omega_cmd_rad_s[0], 812.5);
  EXPECT_EQ(sample.omega_cmd_rad_s[1], 799.25);
  EXPECT_TRUE(std::isnan(sample.omega_meas_rad_s[0]));
  EXPECT_EQ(sample.omega_meas_rad_s[1], 801.0);
}

TEST(ConversionTest, TruthFieldsMapByName) {
  const TruthSample s = FromMessage(MakeTestMessage<truth_t>());
  EXPECT_EQ(s.utime, 6000005);
  EXPECT_EQ(s.x_m, 0.1);
  EXPECT_EQ(s.z_m, 0.2);
  EXPECT_EQ(s.phi_rad, 0.3);
  EXPECT_EQ(s.deflection_rad[0], -0.01);
  EXPECT_EQ(s.deflection_rad[1], 0.02);
  EXPECT_EQ(s.x_dot_m_s, 0.4);
  EXPECT_EQ(s.z_dot_m_s, 0.5);
  EXPECT_EQ(s.phi_dot_rad_s, 0.6);
  EXPECT_EQ(s.deflection_dot_rad_s[0], 0.7);
  EXPECT_EQ(s.deflection_dot_rad_s[1], 0.8);
  EXPECT_EQ(s.omega_rad_s[0], 900);
  EXPECT_EQ(s.omega_rad_s[1], 910);
  EXPECT_EQ(s.force_n[0], 5.1);
  EXPECT_EQ(s.force_n[1], 5.2);
  EXPECT_EQ(s.thrust_scale[0], 1.0);
  EXPECT_EQ(s.thrust_scale[1], 0.75);
}

TEST(ConversionTest, ForceEstimateFromSample) {
  ForceEstimate estimate;
  estimate.utime = 99;
  estimate.seq = 98;
  estimate.force_n[0] = 4.0;
  estimate.force_n[1] = 4.5;
  estimate.force_std_n[0] = 0.1;
  estimate.force_std_n[1] = 0.2;
  estimate.thrust_scale[0] = 0.9;
  estimate.thrust_scale[1] = 1.1;
  estimate.status = kStatusValid | kStatusRotor1Fault;
  const force_estimate_t m = ToMessage(estimate);
  EXPECT_EQ(m.utime, 99);
  EXPECT_EQ(m.seq, 98);
  EXPECT_EQ(m.force_n[0], 4.0);
  EXPECT_EQ(m.force_n[1], 4.5);
  EXPECT_EQ(m.force_std_n[0], 0.1);
  EXPECT_EQ(m.force_std_n[1], 0.2);
  EXPECT_EQ(m.thrust_scale[0], 0.9);
  EXPECT_EQ(m.thrust_scale[1], 1.1);
  EXPECT_EQ(m.status, force_estimate_t::STATUS_VALID | force_estimate_t::STATUS_ROTOR1_FAULT);
}

TEST(ConversionTest, StatusBitsMatchTheWireConstants) {
  EXPECT_EQ(kStatusValid, force_estimate_t::STATUS_VALID);
  EXPECT_EQ(kStatusConverging, force_estimate_t::STATUS_CONVERGING);
  EXPECT_EQ(kStatusMeasurementRejected, force_estimate_t::STATUS_MEASUREMENT_REJECTED);
  EXPECT_EQ(kStatusInputStale, force_estimate_t::STATUS_INPUT_STALE);
  EXPECT_EQ(kStatusRotor1Fault, force_estimate_t::STATUS_ROTOR1_FAULT);
  EXPECT_EQ(kStatusRotor2Fault, force_estimate_t::STATUS_ROTOR2_FAULT);
  EXPECT_EQ(kStatusFilterReset, force_estimate_t::STATUS_FILTER_RESET);
  EXPECT_EQ(kStatusModelMismatch, force_estimate_t::STATUS_MODEL_MISMATCH);
  EXPECT_EQ(kStatusNoMotorInput, force_estimate_t::STATUS_NO_MOTOR_INPUT);
}

TEST(ConversionTest, MotorCommandConstantsMatchTheLcmFile) {
  EXPECT_EQ(kModeNominal, motor_command_t::MODE_NOMINAL);
  EXPECT_EQ(kModeForceFeedback, motor_command_t::MODE_FORCE_FEEDBACK);
  EXPECT_EQ(kCommandFallbackActive, motor_command_t::STATUS_FALLBACK_ACTIVE);
  EXPECT_EQ(kCommandInputStale, motor_command_t::STATUS_INPUT_STALE);
  EXPECT_EQ(kCommandDescending, motor_command_t::STATUS_DESCENDING);
  EXPECT_EQ(kCommandSaturated, motor_command_t::STATUS_SATURATED);
  EXPECT_EQ(kCommandNoPoseYet, motor_command_t::STATUS_NO_POSE_YET);
  EXPECT_EQ(kModeMpc, motor_command_t::MODE_MPC);
  EXPECT_EQ(kCommandMpcFallback, motor_command_t::STATUS_MPC_FALLBACK);
}

}  // namespace
}  // namespace birotor
