// Field-by-field copies between wire messages and sample structs. Both sides
// use the same field names, so one field list per type serves both
// directions (a field added to a type is added in one place).
#include "transport/message_conversion.h"

namespace birotor {
namespace {

// Copies a two-element per-rotor array (rotor 1, rotor 2).
void CopyPair(const double (&from)[2], double (&to)[2]) {
  to[0] = from[0];
  to[1] = from[1];
}

template <typename From, typename To>
void CopyStrainFields(const From& from, To* to) {
  to->utime = from.utime;
  to->seq = from.seq;
  CopyPair(from.deflection_rad, to->deflection_rad);
}

template <typename From, typename To>
void CopyMotorFields(const From& from, To* to) {
  to->utime = from.utime;
  to->seq = from.seq;
  CopyPair(from.omega_cmd_rad_s, to->omega_cmd_rad_s);
  CopyPair(from.omega_meas_rad_s, to->omega_meas_rad_s);
}

template <typename From, typename To>
void CopyImuFields(const From& from, To* to) {
  to->utime = from.utime;
  to->seq = from.seq;
  to->gyro_y_rad_s = from.gyro_y_rad_s;
  to->accel_x_m_s2 = from.accel_x_m_s2;
  to->accel_z_m_s2 = from.accel_z_m_s2;
}

template <typename From, typename To>
void CopyPoseFields(const From& from, To* to) {
  to->utime = from.utime;
  to->seq = from.seq;
  to->x_m = from.x_m;
  to->z_m = from.z_m;
  to->phi_rad = from.phi_rad;
}

template <typename From, typename To>
void CopyLoadCellFields(const From& from, To* to) {
  to->utime = from.utime;
  to->seq = from.seq;
  CopyPair(from.force_n, to->force_n);
}

template <typename From, typename To>
void CopyTruthFields(const From& from, To* to) {
  to->utime = from.utime;
  to->x_m = from.x_m;
  to->z_m = from.z_m;
  to->phi_rad = from.phi_rad;
  CopyPair(from.deflection_rad, to->deflection_rad);
  to->x_dot_m_s = from.x_dot_m_s;
  to->z_dot_m_s = from.z_dot_m_s;
  to->phi_dot_rad_s = from.phi_dot_rad_s;
  CopyPair(from.deflection_dot_rad_s, to->deflection_dot_rad_s);
  CopyPair(from.omega_rad_s, to->omega_rad_s);
  CopyPair(from.force_n, to->force_n);
  CopyPair(from.thrust_scale, to->thrust_scale);
}

template <typename From, typename To>
void CopyForceFields(const From& from, To* to) {
  to->utime = from.utime;
  to->seq = from.seq;
  CopyPair(from.force_n, to->force_n);
  CopyPair(from.force_std_n, to->force_std_n);
  CopyPair(from.thrust_scale, to->thrust_scale);
  to->status = from.status;
}

template <typename From, typename To>
void CopyMotorCommandFields(const From& from, To* to) {
  to->utime = from.utime;
  to->seq = from.seq;
  CopyPair(from.omega_cmd_rad_s, to->omega_cmd_rad_s);
  to->mode = from.mode;
  to->status = from.status;
}

template <typename From, typename To>
void CopySetpointFields(const From& from, To* to) {
  to->utime = from.utime;
  to->seq = from.seq;
  to->x_m = from.x_m;
  to->z_m = from.z_m;
  to->x_dot_m_s = from.x_dot_m_s;
  to->z_dot_m_s = from.z_dot_m_s;
  to->x_ddot_m_s2 = from.x_ddot_m_s2;
  to->z_ddot_m_s2 = from.z_ddot_m_s2;
}

// To{} zero-initialises the message's fields that the list does not name.
template <typename To, typename From>
To Converted(const From& from, void (*copy)(const From&, To*)) {
  To to{};
  copy(from, &to);
  return to;
}

}  // namespace

StrainSample FromMessage(const strain_t& m) { return Converted<StrainSample>(m, CopyStrainFields); }
strain_t ToMessage(const StrainSample& s) { return Converted<strain_t>(s, CopyStrainFields); }
MotorSample FromMessage(const motor_t& m) { return Converted<MotorSample>(m, CopyMotorFields); }
motor_t ToMessage(const MotorSample& s) { return Converted<motor_t>(s, CopyMotorFields); }
ImuSample FromMessage(const imu_t& m) { return Converted<ImuSample>(m, CopyImuFields); }
imu_t ToMessage(const ImuSample& s) { return Converted<imu_t>(s, CopyImuFields); }
PoseSample FromMessage(const pose_t& m) { return Converted<PoseSample>(m, CopyPoseFields); }
pose_t ToMessage(const PoseSample& s) { return Converted<pose_t>(s, CopyPoseFields); }
LoadCellSample FromMessage(const loadcell_t& m) { return Converted<LoadCellSample>(m, CopyLoadCellFields); }
loadcell_t ToMessage(const LoadCellSample& s) { return Converted<loadcell_t>(s, CopyLoadCellFields); }
TruthSample FromMessage(const truth_t& m) { return Converted<TruthSample>(m, CopyTruthFields); }
truth_t ToMessage(const TruthSample& s) { return Converted<truth_t>(s, CopyTruthFields); }
ForceEstimate FromMessage(const force_estimate_t& m) { return Converted<ForceEstimate>(m, CopyForceFields); }
force_estimate_t ToMessage(const ForceEstimate& e) { return Converted<force_estimate_t>(e, CopyForceFields); }

MotorCommand FromMessage(const motor_command_t& m) { return Converted<MotorCommand>(m, CopyMotorCommandFields); }
motor_command_t ToMessage(const MotorCommand& c) { return Converted<motor_command_t>(c, CopyMotorCommandFields); }
Setpoint FromMessage(const setpoint_t& m) { return Converted<Setpoint>(m, CopySetpointFields); }
setpoint_t ToMessage(const Setpoint& s) { return Converted<setpoint_t>(s, CopySetpointFields); }

}  // namespace birotor
