// LCM channel names: <prefix><base name>, default prefix "BIROTOR_", so several
// vehicles can share one LCM network (see shared/spec/interface.md).
#pragma once

#include <cstddef>
#include <string>

namespace birotor {

inline constexpr char kDefaultChannelPrefix[] = "BIROTOR_";

// Base names, without the prefix.
inline constexpr char kStrainChannel[] = "STRAIN";
inline constexpr char kMotorChannel[] = "MOTOR";
inline constexpr char kImuChannel[] = "IMU";
inline constexpr char kPoseChannel[] = "POSE";
inline constexpr char kLoadCellChannel[] = "LOADCELL";
inline constexpr char kTruthChannel[] = "TRUTH";
inline constexpr char kForceChannel[] = "FORCE";
inline constexpr char kEstimatorStatusChannel[] = "ESTIMATOR_STATUS";
inline constexpr char kSimStatusChannel[] = "SIM_STATUS";
inline constexpr char kMotorCommandChannel[] = "MOTOR_COMMAND";
inline constexpr char kControllerStatusChannel[] = "CONTROLLER_STATUS";
inline constexpr char kSetpointChannel[] = "SETPOINT";
// The counted types for a vehicle with N arms (docs/interface.md, "Vehicles
// with N arms"): new names, because a channel carries one type (lcm-spy and
// the tools decode a channel by it), and the birotor channels keep theirs.
inline constexpr char kStrainNChannel[] = "STRAIN_N";
inline constexpr char kMotorNChannel[] = "MOTOR_N";
inline constexpr char kLoadCellNChannel[] = "LOADCELL_N";
inline constexpr char kTruthNChannel[] = "TRUTH_N";
inline constexpr char kForceNChannel[] = "FORCE_N";
inline constexpr char kMotorCommandNChannel[] = "MOTOR_COMMAND_N";
// controller_rotors_n_t: the N-rotor controller's per-rotor status, with CONTROLLER_STATUS.
inline constexpr char kControllerRotorsNChannel[] = "CONTROLLER_ROTORS_N";
// estimator_learned_n_t: the estimator's learned values per arm, with ESTIMATOR_STATUS.
inline constexpr char kEstimatorLearnedNChannel[] = "ESTIMATOR_LEARNED_N";
// vehicle_description_t.
inline constexpr char kVehicleDescriptionChannel[] = "VEHICLE";
// The authenticated types of the channels whose forgery moves the vehicle
// (docs/interface.md, "Authenticated channels"): <type>_auth_t, each on its
// own channel beside the plain one.
inline constexpr char kMotorCommandAuthChannel[] = "MOTOR_COMMAND_AUTH";
inline constexpr char kSetpointAuthChannel[] = "SETPOINT_AUTH";
inline constexpr char kPoseAuthChannel[] = "POSE_AUTH";
inline constexpr char kForceAuthChannel[] = "FORCE_AUTH";
// The sealed twins of the N-arm channels MOTOR_COMMAND_N and FORCE_N
// (motor_command_n_auth_t, force_estimate_n_auth_t), the same seal.
inline constexpr char kMotorCommandNAuthChannel[] = "MOTOR_COMMAND_N_AUTH";
inline constexpr char kForceNAuthChannel[] = "FORCE_N_AUTH";
// guard_status_t: what each program sealed and refused.
inline constexpr char kGuardStatusChannel[] = "GUARD_STATUS";

// Full channel names for one prefix.
struct ChannelNames {
  std::string prefix;
  std::string strain;                // strain_t
  std::string motor;                 // motor_t
  std::string imu;                   // imu_t
  std::string pose;                  // pose_t
  std::string loadcell;              // loadcell_t
  std::string truth;                 // truth_t
  std::string force;                 // force_estimate_t
  std::string estimator_status;      // estimator_status_t
  std::string sim_status;            // simulator health, owned by simulator/
  std::string motor_command;         // motor_command_t
  std::string controller_status;     // controller_status_t
  std::string setpoint;              // setpoint_t
  std::string strain_n;              // strain_n_t
  std::string motor_n;               // motor_n_t
  std::string loadcell_n;            // loadcell_n_t
  std::string truth_n;               // truth_n_t
  std::string force_n;               // force_estimate_n_t
  std::string motor_command_n;       // motor_command_n_t
  std::string controller_rotors_n;   // controller_rotors_n_t
  std::string estimator_learned_n;   // estimator_learned_n_t
  std::string vehicle;               // vehicle_description_t
  std::string motor_command_auth;    // motor_command_auth_t
  std::string setpoint_auth;         // setpoint_auth_t
  std::string pose_auth;             // pose_auth_t
  std::string force_auth;            // force_estimate_auth_t
  std::string motor_command_n_auth;  // motor_command_n_auth_t
  std::string force_n_auth;          // force_estimate_n_auth_t
  std::string guard_status;          // guard_status_t
};

ChannelNames MakeChannelNames(const std::string& prefix = kDefaultChannelPrefix);

// Longest prefix whose every channel fits LCM's channel-name limit
// (LCM_MAX_CHANNEL_NAME_LENGTH, 63 bytes) with the longest base name,
// MOTOR_COMMAND_N_AUTH: 63 - 20 = 43 bytes (45 before the N-arm sealed
// twins; docs/interface.md, "Authenticated channels").
inline constexpr size_t kMaxChannelPrefixBytes = 63 - (sizeof(kMotorCommandNAuthChannel) - 1);

// "" when prefix is usable, else one line saying why: longer than
// kMaxChannelPrefixBytes (LCM would refuse every publish on the longest
// channels), or a byte outside printable ASCII without space (LC02 channel
// names are read as printable ASCII; such a channel would be dropped).
std::string ChannelPrefixProblem(const std::string& prefix);

}  // namespace birotor
