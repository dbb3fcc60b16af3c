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
  return names;
}

}  // namespace birotor
