// Channel names from a prefix.
#include "transport/channels.h"

namespace birotor {

ChannelNames MakeChannelNames(const std::string& prefix) {
  ChannelNames names;
  names.prefix = prefix;
  names.strain = prefix + kStrainChannel;
  names.motor = prefix + kMotorChannel;
  names.imu = prefix + kImuChannel;
  names.pose = prefix + kPoseChannel;
  names.loadcell = prefix + kLoadCellChannel;
  names.truth = prefix + kTruthChannel;
  names.force = prefix + kForceChannel;
  names.estimator_status = prefix + kEstimatorStatusChannel;
  names.sim_status = prefix + kSimStatusChannel;
  names.motor_command = prefix + kMotorCommandChannel;
  names.controller_status = prefix + kControllerStatusChannel;
  names.setpoint = prefix + kSetpointChannel;
  names.strain_n = prefix + kStrainNChannel;
  names.motor_n = prefix + kMotorNChannel;
  names.loadcell_n = prefix + kLoadCellNChannel;
  names.truth_n = prefix + kTruthNChannel;
  names.force_n = prefix + kForceNChannel;
  names.motor_command_n = prefix + kMotorCommandNChannel;
  names.controller_rotors_n = prefix + kControllerRotorsNChannel;
  names.estimator_learned_n = prefix + kEstimatorLearnedNChannel;
  names.vehicle = prefix + kVehicleDescriptionChannel;
  names.motor_command_auth = prefix + kMotorCommandAuthChannel;
  names.setpoint_auth = prefix + kSetpointAuthChannel;
  names.pose_auth = prefix + kPoseAuthChannel;
  names.force_auth = prefix + kForceAuthChannel;
  names.motor_command_n_auth = prefix + kMotorCommandNAuthChannel;
  names.force_n_auth = prefix + kForceNAuthChannel;
  names.guard_status = prefix + kGuardStatusChannel;
  return names;
}

std::string ChannelPrefixProblem(const std::string& prefix) {
  if (prefix.size() > kMaxChannelPrefixBytes) {
    return "channel prefix of " + std::to_string(prefix.size()) + " bytes is longer than " +
           std::to_string(kMaxChannelPrefixBytes) + " (LCM channel names are at most 63 bytes, " +
           kMotorCommandNAuthChannel + " takes " + std::to_string(sizeof(kMotorCommandNAuthChannel) - 1) + ")";
  }
  for (const char c : prefix) {
    if (c <= ' ' || c > '~') return "channel prefix has a byte outside printable ASCII (or a space)";
  }
  return "";
}

}  // namespace birotor
