// Tests of transport/channels.h.
#include "transport/channels.h"

#include <gtest/gtest.h>

#include <string>

namespace birotor {
namespace {

TEST(ChannelsTest, DefaultPrefix) {
  const ChannelNames names = MakeChannelNames();
  EXPECT_EQ(names.prefix, "BIROTOR_");
  EXPECT_EQ(names.strain, "BIROTOR_STRAIN");
  EXPECT_EQ(names.motor, "BIROTOR_MOTOR");
  EXPECT_EQ(names.imu, "BIROTOR_IMU");
  EXPECT_EQ(names.pose, "BIROTOR_POSE");
  EXPECT_EQ(names.loadcell, "BIROTOR_LOADCELL");
  EXPECT_EQ(names.truth, "BIROTOR_TRUTH");
  EXPECT_EQ(names.force, "BIROTOR_FORCE");
  EXPECT_EQ(names.estimator_status, "BIROTOR_ESTIMATOR_STATUS");
  EXPECT_EQ(names.sim_status, "BIROTOR_SIM_STATUS");
  EXPECT_EQ(names.motor_command, "BIROTOR_MOTOR_COMMAND");
  EXPECT_EQ(names.controller_status, "BIROTOR_CONTROLLER_STATUS");
  EXPECT_EQ(names.strain_n, "BIROTOR_STRAIN_N");
  EXPECT_EQ(names.motor_n, "BIROTOR_MOTOR_N");
  EXPECT_EQ(names.loadcell_n, "BIROTOR_LOADCELL_N");
  EXPECT_EQ(names.truth_n, "BIROTOR_TRUTH_N");
  EXPECT_EQ(names.force_n, "BIROTOR_FORCE_N");
  EXPECT_EQ(names.motor_command_n, "BIROTOR_MOTOR_COMMAND_N");
  EXPECT_EQ(names.controller_rotors_n, "BIROTOR_CONTROLLER_ROTORS_N");
  EXPECT_EQ(names.estimator_learned_n, "BIROTOR_ESTIMATOR_LEARNED_N");
  EXPECT_EQ(names.vehicle, "BIROTOR_VEHICLE");
}

TEST(ChannelsTest, MotorCommandNAuthStaysTheLongestBaseName) {
  // The prefix limit is computed from it; a longer new name would shorten it.
  for (const char* name : {kStrainChannel,
                           kMotorChannel,
                           kImuChannel,
                           kPoseChannel,
                           kLoadCellChannel,
                           kTruthChannel,
                           kForceChannel,
                           kEstimatorStatusChannel,
                           kSimStatusChannel,
                           kMotorCommandChannel,
                           kControllerStatusChannel,
                           kSetpointChannel,
                           kStrainNChannel,
                           kMotorNChannel,
                           kLoadCellNChannel,
                           kTruthNChannel,
                           kForceNChannel,
                           kMotorCommandNChannel,
                           kControllerRotorsNChannel,
                           kEstimatorLearnedNChannel,
                           kVehicleDescriptionChannel,
                           kMotorCommandAuthChannel,
                           kSetpointAuthChannel,
                           kPoseAuthChannel,
                           kForceAuthChannel,
                           kForceNAuthChannel,
                           kGuardStatusChannel}) {
    EXPECT_LE(std::string(name).size(), sizeof(kMotorCommandNAuthChannel) - 1) << name;
  }
}

TEST(ChannelsTest, CustomAndEmptyPrefix) {
  EXPECT_EQ(MakeChannelNames("VEHICLE2_").force, "VEHICLE2_FORCE");
  EXPECT_EQ(MakeChannelNames("").strain, "STRAIN");
}

// Issue 23 item 8: the prefix is checked against LCM's 63-byte channel limit.
TEST(ChannelsTest, PrefixLongerThanTheChannelLimitIsAProblem) {
  EXPECT_EQ(kMaxChannelPrefixBytes, 43u);  // 63 - strlen("MOTOR_COMMAND_N_AUTH")
  EXPECT_EQ(ChannelPrefixProblem(std::string(43, 'P')), "");
  EXPECT_EQ(MakeChannelNames(std::string(43, 'P')).motor_command_n_auth.size(), 63u);
  EXPECT_EQ(ChannelPrefixProblem(std::string(44, 'P')),
            "channel prefix of 44 bytes is longer than 43 (LCM channel names are at most 63 bytes, "
            "MOTOR_COMMAND_N_AUTH takes 20)");
  EXPECT_NE(ChannelPrefixProblem("A B_"), "");
  EXPECT_NE(ChannelPrefixProblem("A\nB_"), "");
  EXPECT_EQ(ChannelPrefixProblem(kDefaultChannelPrefix), "");
  EXPECT_EQ(ChannelPrefixProblem(""), "");
}

}  // namespace
}  // namespace birotor
