// The field list of every birotor wire type, one template per type that
// copies From -> To by field name: message <-> sample struct
// (message_conversion.cc) and birotor message <-> its counted twin with
// n = 2 (counted_messages.cc). A field added to a type is added here once.
// Internal to transport/.
#pragma once

#include <vector>

#include "samples/rotor_count.h"

namespace birotor::internal {

// Copies a two-element per-rotor array (rotor 1, rotor 2): between the
// birotor's fixed arrays, and to and from a counted message's array (a
// vector the caller has checked holds two).
inline void CopyPair(const double (&from)[kBirotorRotors], double (&to)[kBirotorRotors]) {
  to[0] = from[0];
  to[1] = from[1];
}
inline void CopyPair(const double (&from)[kBirotorRotors], std::vector<double>& to) {
  to.assign(from, from + kBirotorRotors);
}
inline void CopyPair(const std::vector<double>& from, double (&to)[kBirotorRotors]) {
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

}  // namespace birotor::internal
