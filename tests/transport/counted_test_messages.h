// Filled-in examples of the counted (_n_t) wire types for any count, shared
// by the transport tests; MakeTestMessage<T>() is the trirotor's (n = 3).
// Values are distinct per field and per element, so a swapped or dropped
// field or element shows.
#pragma once

#include <limits>
#include <vector>

#include "birotor/controller_rotors_n_t.hpp"
#include "birotor/estimator_learned_n_t.hpp"
#include "birotor/force_estimate_n_t.hpp"
#include "birotor/loadcell_n_t.hpp"
#include "birotor/motor_command_n_t.hpp"
#include "birotor/motor_n_t.hpp"
#include "birotor/strain_n_t.hpp"
#include "birotor/truth_n_t.hpp"
#include "birotor/vehicle_description_t.hpp"
#include "tests/transport/test_messages.h"

namespace birotor::transport_test {

// n values base + 0.125 i (exact in binary), i = 0 .. n-1.
inline std::vector<double> Ramp(int n, double base) {
  std::vector<double> values;
  for (int i = 0; i < n; ++i) values.push_back(base + 0.125 * i);
  return values;
}

template <class Msg>
Msg MakeCountedTestMessage(int n);

template <>
inline strain_n_t MakeCountedTestMessage<strain_n_t>(int n) {
  strain_n_t m{};
  m.utime = 1234567;
  m.seq = 42;
  m.n_arms = static_cast<int8_t>(n);
  m.deflection_rad = Ramp(n, -0.0123);
  return m;
}

template <>
inline motor_n_t MakeCountedTestMessage<motor_n_t>(int n) {
  motor_n_t m{};
  m.utime = 2000001;
  m.seq = -7;
  m.n_rotors = static_cast<int8_t>(n);
  m.omega_cmd_rad_s = Ramp(n, 812.5);
  m.omega_meas_rad_s = Ramp(n, 801.0);
  if (n > 0) m.omega_meas_rad_s[0] = std::numeric_limits<double>::quiet_NaN();  // no telemetry on rotor 1
  return m;
}

template <>
inline loadcell_n_t MakeCountedTestMessage<loadcell_n_t>(int n) {
  loadcell_n_t m{};
  m.utime = 5000003;
  m.seq = 9;
  m.n_rotors = static_cast<int8_t>(n);
  m.force_n = Ramp(n, 19.5);
  return m;
}

template <>
inline truth_n_t MakeCountedTestMessage<truth_n_t>(int n) {
  truth_n_t m{};
  m.utime = 6000005;
  m.x_m = 0.1;
  m.z_m = 0.2;
  m.phi_rad = 0.3;
  m.n_arms = static_cast<int8_t>(n);
  m.deflection_rad = Ramp(n, -0.01);
  m.x_dot_m_s = 0.4;
  m.z_dot_m_s = 0.5;
  m.phi_dot_rad_s = 0.6;
  m.deflection_dot_rad_s = Ramp(n, 0.7);
  m.omega_rad_s = Ramp(n, 810.0);
  m.force_n = Ramp(n, 20.0);
  m.thrust_scale = Ramp(n, 0.75);
  return m;
}

template <>
inline force_estimate_n_t MakeCountedTestMessage<force_estimate_n_t>(int n) {
  force_estimate_n_t m{};
  m.utime = 3000002;
  m.seq = 77;
  m.n_rotors = static_cast<int8_t>(n);
  m.force_n = Ramp(n, 19.75);
  m.force_std_n = Ramp(n, 0.25);
  m.thrust_scale = Ramp(n, 0.5);
  m.status = force_estimate_n_t::STATUS_VALID | force_estimate_n_t::STATUS_THRUST_DEFICIT;
  m.rotor_fault_bits = force_estimate_n_t::ROTOR_FAULT_ROTOR2;
  return m;
}

template <>
inline motor_command_n_t MakeCountedTestMessage<motor_command_n_t>(int n) {
  motor_command_n_t m{};
  m.utime = 2500004;
  m.seq = 1001;
  m.n_rotors = static_cast<int8_t>(n);
  m.omega_cmd_rad_s = Ramp(n, 700.5);
  m.mode = motor_command_n_t::MODE_FORCE_FEEDBACK;
  m.status = motor_command_n_t::STATUS_SATURATED;
  return m;
}

template <>
inline vehicle_description_t MakeCountedTestMessage<vehicle_description_t>(int n) {
  vehicle_description_t m{};
  m.utime = 7000000;
  m.seq = 3;
  m.publisher = "birotor-test";
  m.name = "ramp";
  m.checksum = "0123456789abcdef";  // not the fields' checksum: a wire test only
  m.body_mass_kg = 4.0;
  m.body_inertia_kg_m2 = 0.05;
  m.gravity_m_s2 = 9.81;
  m.omega_max_rad_s = 1200.0;
  m.turbulence_std = 0.01;
  m.turbulence_corr_time_s = 0.1;
  m.gauge_offset_std_rad = 5e-5;
  m.gauge_drift_psd_rad2_s = 1e-10;
  m.n_arms = static_cast<int8_t>(n);
  m.angle_rad = Ramp(n, 0.0);
  m.length_m = Ramp(n, 0.25);
  m.thrust_angle_rad = Ramp(n, -0.125);
  m.spin.assign(static_cast<size_t>(n), 1);
  if (n > 0) m.spin[0] = -1;
  m.stiffness_n_m_rad = Ramp(n, 2628.0);
  m.damping_n_m_s_rad = Ramp(n, 0.25);
  m.tip_mass_kg = Ramp(n, 0.28812);
  m.thrust_coeff_n_s2_rad2 = Ramp(n, 4.6e-5);
  m.motor_time_constant_s = Ramp(n, 0.035);
  m.has_gauge.assign(static_cast<size_t>(n), 1);
  if (n > 0) m.has_gauge[0] = 0;
  m.gauge_scale = Ramp(n, 1.0);
  m.gauge_offset_rad = Ramp(n, 0.0);
  return m;
}

template <>
inline controller_rotors_n_t MakeCountedTestMessage<controller_rotors_n_t>(int n) {
  controller_rotors_n_t m{};
  m.utime = 8000007;
  m.seq = 13;
  m.vehicle_checksum = "3c46c6d41f8659af";
  m.n_rotors = static_cast<int8_t>(n);
  m.efficiency = Ramp(n, 0.625);
  m.feasibility_bound = Ramp(n, 0.375);
  m.weak_rotor = static_cast<int8_t>(n - 1);
  m.weak_efficiency = 0.625;
  return m;
}

// The trirotor's examples for the type-parameterised codec tests.
constexpr int kTestArmCount = 3;
template <>
inline strain_n_t MakeTestMessage<strain_n_t>() {
  return MakeCountedTestMessage<strain_n_t>(kTestArmCount);
}
template <>
inline motor_n_t MakeTestMessage<motor_n_t>() {
  return MakeCountedTestMessage<motor_n_t>(kTestArmCount);
}
template <>
inline loadcell_n_t MakeTestMessage<loadcell_n_t>() {
  return MakeCountedTestMessage<loadcell_n_t>(kTestArmCount);
}
template <>
inline truth_n_t MakeTestMessage<truth_n_t>() {
  return MakeCountedTestMessage<truth_n_t>(kTestArmCount);
}
template <>
inline force_estimate_n_t MakeTestMessage<force_estimate_n_t>() {
  return MakeCountedTestMessage<force_estimate_n_t>(kTestArmCount);
}
template <>
inline motor_command_n_t MakeTestMessage<motor_command_n_t>() {
  return MakeCountedTestMessage<motor_command_n_t>(kTestArmCount);
}
template <>
inline vehicle_description_t MakeTestMessage<vehicle_description_t>() {
  return MakeCountedTestMessage<vehicle_description_t>(kTestArmCount);
}
template <>
inline controller_rotors_n_t MakeTestMessage<controller_rotors_n_t>() {
  return MakeCountedTestMessage<controller_rotors_n_t>(kTestArmCount);
}
// Every source string differs in length, so a walker that skips the wrong
// one fails the round trip.
template <>
inline estimator_learned_n_t MakeTestMessage<estimator_learned_n_t>() {
  estimator_learned_n_t m{};
  m.utime = 4000003;
  m.seq = 19;
  m.vehicle_checksum = "0123456789abcdef";
  m.n_arms = static_cast<int8_t>(kTestArmCount);
  m.strain_scale = Ramp(kTestArmCount, 1.0);
  m.strain_scale_std = Ramp(kTestArmCount, 0.0625);
  m.strain_scale_source = "learned";
  m.tip_mass_kg = Ramp(kTestArmCount, 0.25);
  m.tip_mass_std_kg = Ramp(kTestArmCount, 0.03125);
  m.tip_mass_source = "state_file";
  m.strain_noise_rad = Ramp(kTestArmCount, 2e-5);
  m.strain_noise_source = "params";
  m.body_mass_kg = 4.0;
  m.body_mass_std_kg = std::numeric_limits<double>::quiet_NaN();
  m.body_mass_source = "";
  return m;
}

}  // namespace birotor::transport_test
