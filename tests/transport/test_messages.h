// Filled-in example of every wire type, shared by the transport tests. Values
// are distinct per field so a swapped or dropped field shows.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/input_health_t.hpp"
#include "birotor/loadcell_t.hpp"
#include "birotor/motor_command_t.hpp"
#include "birotor/motor_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/strain_t.hpp"
#include "birotor/truth_t.hpp"
#include "transport/lcm_codec.h"

namespace birotor::transport_test {

// The wire bytes of msg (transport/lcm_codec.h).
template <class Msg>
std::vector<uint8_t> Encode(const Msg& msg) {
  std::vector<uint8_t> bytes;
  EncodeMessage(msg, &bytes);
  return bytes;
}

template <class Msg>
Msg MakeTestMessage();

template <>
inline strain_t MakeTestMessage<strain_t>() {
  strain_t m{};
  m.utime = 1234567;
  m.seq = 42;
  m.deflection_rad[0] = -0.0123;
  m.deflection_rad[1] = 0.0125;
  return m;
}

template <>
inline motor_t MakeTestMessage<motor_t>() {
  motor_t m{};
  m.utime = 2000001;
  m.seq = -7;  // seq wraps, so negative values travel too
  m.omega_cmd_rad_s[0] = 812.5;
  m.omega_cmd_rad_s[1] = 799.25;
  m.omega_meas_rad_s[0] = std::numeric_limits<double>::quiet_NaN();
  m.omega_meas_rad_s[1] = 801.0;
  return m;
}

template <>
inline motor_command_t MakeTestMessage<motor_command_t>() {
  motor_command_t m{};
  m.utime = 2500004;
  m.seq = -9;
  m.omega_cmd_rad_s[0] = 705.5;
  m.omega_cmd_rad_s[1] = 744.125;
  m.mode = motor_command_t::MODE_FORCE_FEEDBACK;
  m.status = motor_command_t::STATUS_FALLBACK_ACTIVE | motor_command_t::STATUS_INPUT_STALE;
  return m;
}

template <>
inline imu_t MakeTestMessage<imu_t>() {
  imu_t m{};
  m.utime = 3000002;
  m.seq = 3;
  m.gyro_y_rad_s = 0.25;
  m.accel_x_m_s2 = -0.5;
  m.accel_z_m_s2 = 9.81;
  return m;
}

template <>
inline pose_t MakeTestMessage<pose_t>() {
  pose_t m{};
  m.utime = 4000003;
  m.seq = 4;
  m.x_m = 1.5;
  m.z_m = 2.25;
  m.phi_rad = -0.125;
  return m;
}

template <>
inline loadcell_t MakeTestMessage<loadcell_t>() {
  loadcell_t m{};
  m.utime = 5000004;
  m.seq = 5;
  m.force_n[0] = 4.5;
  m.force_n[1] = 4.75;
  return m;
}

template <>
inline truth_t MakeTestMessage<truth_t>() {
  truth_t m{};
  m.utime = 6000005;
  m.x_m = 0.1;
  m.z_m = 0.2;
  m.phi_rad = 0.3;
  m.deflection_rad[0] = -0.01;
  m.deflection_rad[1] = 0.02;
  m.x_dot_m_s = 0.4;
  m.z_dot_m_s = 0.5;
  m.phi_dot_rad_s = 0.6;
  m.deflection_dot_rad_s[0] = 0.7;
  m.deflection_dot_rad_s[1] = 0.8;
  m.omega_rad_s[0] = 900;
  m.omega_rad_s[1] = 910;
  m.force_n[0] = 5.1;
  m.force_n[1] = 5.2;
  m.thrust_scale[0] = 1.0;
  m.thrust_scale[1] = 0.75;
  return m;
}

template <>
inline force_estimate_t MakeTestMessage<force_estimate_t>() {
  force_estimate_t m{};
  m.utime = 7000006;
  m.seq = 6;
  m.force_n[0] = 5.0;
  m.force_n[1] = std::numeric_limits<double>::quiet_NaN();
  m.force_std_n[0] = 0.05;
  m.force_std_n[1] = 0.06;
  m.thrust_scale[0] = 0.98;
  m.thrust_scale[1] = 0.76;
  m.status = force_estimate_t::STATUS_VALID | force_estimate_t::STATUS_ROTOR2_FAULT;
  return m;
}

inline input_health_t MakeInputHealth(const char* channel, int64_t base) {
  input_health_t h{};
  h.channel = channel;
  h.received = base + 1;
  h.fused = base + 2;
  h.rejected_gate = base + 3;
  h.rejected_invalid = base + 4;
  h.decode_errors = base + 5;
  h.out_of_order = base + 6;
  h.duplicates = base + 7;
  h.gaps = base + 8;
  h.missing_samples = base + 9;
  h.reading_missing = base + 12;
  h.dropped_overload = base + 10;
  h.age_s = 0.001 * static_cast<double>(base);
  h.rate_hz = 1000.0;
  h.not_fused = base + 13;
  h.time_outliers = base + 14;
  h.conflicts = base + 15;
  h.conflict_active = 1;
  h.nis_mean = 2.0;
  h.nis_max = 9.5;
  h.gate = 30.0;
  return h;
}

template <>
inline input_health_t MakeTestMessage<input_health_t>() {
  return MakeInputHealth("STRAIN", 100);
}

template <>
inline estimator_status_t MakeTestMessage<estimator_status_t>() {
  estimator_status_t m{};
  m.utime = 8000007;
  m.wall_utime = 1700000000000000;
  m.seq = 8;
  m.method = "ekf";
  m.status = force_estimate_t::STATUS_VALID;
  m.inputs = {MakeInputHealth("STRAIN", 10), MakeInputHealth("MOTOR", 20), MakeInputHealth("IMU", 30),
              MakeInputHealth("POSE", 40)};
  m.num_inputs = static_cast<int32_t>(m.inputs.size());
  m.strain_nis_mean = 1.9;
  m.strain_nis_max = 12.5;
  m.strain_gate = 13.8;
  m.processing_time_mean_us = 12.0;
  m.processing_time_p99_us = 30.0;
  m.processing_time_max_us = 55.0;
  m.resets = 1;
  m.last_reset_reason = "start";
  m.published = 123456;
  m.force_n[0] = 5.0;
  m.force_n[1] = 5.1;
  m.thrust_scale[0] = 1.0;
  m.thrust_scale[1] = 0.99;
  m.accelerometer = MakeInputHealth("IMU accel_z", 50);
  m.strain_scale[0] = 0.7;
  m.strain_scale[1] = 1.0;
  m.strain_scale_std[0] = 0.01;
  m.strain_scale_std[1] = 0.02;
  m.strain_scale_source = "learned";
  m.body_mass_kg = 4.0;
  m.body_mass_std_kg = 0.05;
  m.body_mass_source = "learned";
  m.vehicle_checksum = "0123456789abcdef";
  return m;
}

}  // namespace birotor::transport_test
