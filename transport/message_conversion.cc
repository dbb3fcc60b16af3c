// Field-by-field copies between wire messages and sample structs.
#include "transport/message_conversion.h"

namespace birotor {
namespace {

// Copies a two-element per-rotor array (rotor 1, rotor 2).
void CopyPair(const double (&from)[2], double (&to)[2]) {
  to[0] = from[0];
  to[1] = from[1];
}

}  // namespace

StrainSample FromMessage(const strain_t& message) {
  StrainSample sample;
  sample.utime = message.utime;
  sample.seq = message.seq;
  CopyPair(message.deflection_rad, sample.deflection_rad);
  return sample;
}

strain_t ToMessage(const StrainSample& sample) {
  strain_t message{};
  message.utime = sample.utime;
  message.seq = sample.seq;
  CopyPair(sample.deflection_rad, message.deflection_rad);
  return message;
}

MotorSample FromMessage(const motor_t& message) {
  MotorSample sample;
  sample.utime = message.utime;
  sample.seq = message.seq;
  CopyPair(message.omega_cmd_rad_s, sample.omega_cmd_rad_s);
  CopyPair(message.omega_meas_rad_s, sample.omega_meas_rad_s);
  return sample;
}

motor_t ToMessage(const MotorSample& sample) {
  motor_t message{};
  message.utime = sample.utime;
  message.seq = sample.seq;
  CopyPair(sample.omega_cmd_rad_s, message.omega_cmd_rad_s);
  CopyPair(sample.omega_meas_rad_s, message.omega_meas_rad_s);
  return message;
}

ImuSample FromMessage(const imu_t& message) {
  ImuSample sample;
  sample.utime = message.utime;
  sample.seq = message.seq;
  sample.gyro_y_rad_s = message.gyro_y_rad_s;
  sample.accel_x_m_s2 = message.accel_x_m_s2;
  sample.accel_z_m_s2 = message.accel_z_m_s2;
  return sample;
}

imu_t ToMessage(const ImuSample& sample) {
  imu_t message{};
  message.utime = sample.utime;
  message.seq = sample.seq;
  message.gyro_y_rad_s = sample.gyro_y_rad_s;
  message.accel_x_m_s2 = sample.accel_x_m_s2;
  message.accel_z_m_s2 = sample.accel_z_m_s2;
  return message;
}

PoseSample FromMessage(const pose_t& message) {
  PoseSample sample;
  sample.utime = message.utime;
  sample.seq = message.seq;
  sample.x_m = message.x_m;
  sample.z_m = message.z_m;
  sample.phi_rad = message.phi_rad;
  return sample;
}

pose_t ToMessage(const PoseSample& sample) {
  pose_t message{};
  message.utime = sample.utime;
  message.seq = sample.seq;
  message.x_m = sample.x_m;
  message.z_m = sample.z_m;
  message.phi_rad = sample.phi_rad;
  return message;
}

LoadCellSample FromMessage(const loadcell_t& message) {
  LoadCellSample sample;
  sample.utime = message.utime;
  sample.seq = message.seq;
  CopyPair(message.force_n, sample.force_n);
  return sample;
}

loadcell_t ToMessage(const LoadCellSample& sample) {
  loadcell_t message{};
  message.utime = sample.utime;
  message.seq = sample.seq;
  CopyPair(sample.force_n, message.force_n);
  return message;
}

TruthSample FromMessage(const truth_t& message) {
  TruthSample sample;
  sample.utime = message.utime;
  sample.x_m = message.x_m;
  sample.z_m = message.z_m;
  sample.phi_rad = message.phi_rad;
  CopyPair(message.deflection_rad, sample.deflection_rad);
  sample.x_dot_m_s = message.x_dot_m_s;
  sample.z_dot_m_s = message.z_dot_m_s;
  sample.phi_dot_rad_s = message.phi_dot_rad_s;
  CopyPair(message.deflection_dot_rad_s, sample.deflection_dot_rad_s);
  CopyPair(message.omega_rad_s, sample.omega_rad_s);
  CopyPair(message.force_n, sample.force_n);
  CopyPair(message.thrust_scale, sample.thrust_scale);
  return sample;
}

truth_t ToMessage(const TruthSample& sample) {
  truth_t message{};
  message.utime = sample.utime;
  message.x_m = sample.x_m;
  message.z_m = sample.z_m;
  message.phi_rad = sample.phi_rad;
  CopyPair(sample.deflection_rad, message.deflection_rad);
  message.x_dot_m_s = sample.x_dot_m_s;
  message.z_dot_m_s = sample.z_dot_m_s;
  message.phi_dot_rad_s = sample.phi_dot_rad_s;
  CopyPair(sample.deflection_dot_rad_s, message.deflection_dot_rad_s);
  CopyPair(sample.omega_rad_s, message.omega_rad_s);
  CopyPair(sample.force_n, message.force_n);
  CopyPair(sample.thrust_scale, message.thrust_scale);
  return message;
}

ForceEstimate FromMessage(const force_estimate_t& message) {
  ForceEstimate estimate;
  estimate.utime = message.utime;
  estimate.seq = message.seq;
  CopyPair(message.force_n, estimate.force_n);
  CopyPair(message.force_std_n, estimate.force_std_n);
  CopyPair(message.thrust_scale, estimate.thrust_scale);
  estimate.status = message.status;
  return estimate;
}

force_estimate_t ToMessage(const ForceEstimate& estimate) {
  force_estimate_t message{};
  message.utime = estimate.utime;
  message.seq = estimate.seq;
  CopyPair(estimate.force_n, message.force_n);
  CopyPair(estimate.force_std_n, message.force_std_n);
  CopyPair(estimate.thrust_scale, message.thrust_scale);
  message.status = estimate.status;
  return message;
}

MotorCommand FromMessage(const motor_command_t& message) {
  MotorCommand command;
  command.utime = message.utime;
  command.seq = message.seq;
  CopyPair(message.omega_cmd_rad_s, command.omega_cmd_rad_s);
  command.mode = message.mode;
  command.status = message.status;
  return command;
}

motor_command_t ToMessage(const MotorCommand& command) {
  motor_command_t message{};
  message.utime = command.utime;
  message.seq = command.seq;
  CopyPair(command.omega_cmd_rad_s, message.omega_cmd_rad_s);
  message.mode = command.mode;
  message.status = command.status;
  return message;
}

}  // namespace birotor
