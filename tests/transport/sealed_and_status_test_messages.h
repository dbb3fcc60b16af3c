// Filled-in examples of the wire types the other two headers leave out: the
// setpoint, the controller's and the guard's status, and the sealed twins
// (<type>_auth_t) of the authenticated channels. Values are distinct per field
// so a swapped or dropped field shows. Shared by the transport tests and the
// decode fuzzer's seed writer (tests/fuzz/write_decode_seeds.cc).
#pragma once

#include <cstdint>
#include <limits>

#include "birotor/controller_status_t.hpp"
#include "birotor/force_estimate_auth_t.hpp"
#include "birotor/force_estimate_n_auth_t.hpp"
#include "birotor/guard_status_t.hpp"
#include "birotor/motor_command_auth_t.hpp"
#include "birotor/motor_command_n_auth_t.hpp"
#include "birotor/pose_auth_t.hpp"
#include "birotor/setpoint_auth_t.hpp"
#include "birotor/setpoint_t.hpp"
#include "tests/transport/counted_test_messages.h"
#include "tests/transport/test_messages.h"

namespace birotor::transport_test {

template <>
inline setpoint_t MakeTestMessage<setpoint_t>() {
  setpoint_t m{};
  m.utime = 9000008;
  m.seq = 10;
  m.x_m = 0.5;
  m.z_m = 1.25;
  m.x_dot_m_s = -0.125;
  m.z_dot_m_s = 0.0625;
  m.x_ddot_m_s2 = 0.03125;
  m.z_ddot_m_s2 = -0.015625;
  return m;
}

// Counters base + 1, base + 2, ... in field order.
template <>
inline controller_status_t MakeTestMessage<controller_status_t>() {
  controller_status_t m{};
  m.utime = 10000009;
  m.wall_utime = 1700000000000001;
  m.seq = 11;
  m.mode = motor_command_t::MODE_FORCE_FEEDBACK;
  m.status = motor_command_t::STATUS_SATURATED;
  m.fallbacks = 1;
  m.descents = 2;
  m.commands = 3;
  m.saturated = 4;
  m.pose_age_s = 0.004;
  m.imu_age_s = std::numeric_limits<double>::quiet_NaN();  // no IMU yet
  m.force_age_s = 0.002;
  for (int i = 0; i < 3; ++i) {
    m.received[i] = 100 + i;
    m.decode_errors[i] = 110 + i;
    m.rejected_invalid[i] = 120 + i;
    m.rejected_out_of_order[i] = 130 + i;
    m.rejected_future[i] = 140 + i;
    m.rejected_past[i] = 150 + i;
    m.rejected_foreign[i] = 160 + i;
  }
  m.pose_rejected_gate = 5;
  m.pose_gate_resets = 6;
  m.conflicts = 7;
  m.infeasible = 8;
  m.clock_relatches = 9;
  m.efficiency[0] = 1.0;
  m.efficiency[1] = 0.75;
  m.setpoint_state = controller_status_t::SETPOINT_FOLLOWING;
  m.setpoint_age_s = 0.02;
  m.setpoint_received = 10;
  m.setpoint_decode_errors = 11;
  m.setpoint_rejected_invalid = 12;
  m.setpoint_rejected_stamp = 13;
  m.setpoint_rejected_out_of_order = 14;
  m.setpoint_rejected_rate = 15;
  m.setpoint_rejected_jump = 16;
  m.setpoint_timeouts = 17;
  m.loop_time_p99_us = 45.5;
  m.loop_time_max_us = 120.25;
  m.mpc_solves = 18;
  m.mpc_fallbacks = 19;
  m.mpc_solve_p50_us = 210.5;
  m.mpc_solve_p99_us = 480.0;
  m.mpc_solve_max_us = 900.75;
  m.mpc_iterations = 20;
  m.mpc_max_iterations = 21;
  m.udp_fragments_dropped = 22;
  m.udp_malformed_dropped = 23;
  return m;
}

template <>
inline guard_status_t MakeTestMessage<guard_status_t>() {
  guard_status_t m{};
  m.utime = 11000010;
  m.wall_utime = 1700000000000002;
  m.seq = 12;
  m.program = guard_status_t::PROGRAM_CONTROLLER;
  m.publisher = 0x0102030405060708;
  m.sealed = 1000;
  for (int i = 0; i < 4; ++i) {
    m.accepted[i] = 200 + i;
    m.refused[i] = 210 + i;
    m.replayed[i] = 220 + i;
    m.unsigned_accepted[i] = 230 + i;
  }
  m.setpoint_rejected_inconsistent = 1;
  m.setpoint_conflicts = 2;
  m.setpoint_rejected_conflict = 3;
  m.setpoint_limited_periods = 4;
  return m;
}

// A sealed twin of message: publisher, counter, a tag of 32 distinct bytes
// (not a valid tag: these are wire tests, not authentication tests).
template <class Sealed, class Plain>
Sealed MakeSealedTestMessage(const Plain& message) {
  Sealed m{};
  m.publisher = 0x1122334455667788;
  m.counter = 9;
  m.message = message;
  for (int i = 0; i < 32; ++i) m.tag[i] = static_cast<int8_t>(7 * i - 100);
  return m;
}

template <>
inline motor_command_auth_t MakeTestMessage<motor_command_auth_t>() {
  return MakeSealedTestMessage<motor_command_auth_t>(MakeTestMessage<motor_command_t>());
}
template <>
inline setpoint_auth_t MakeTestMessage<setpoint_auth_t>() {
  return MakeSealedTestMessage<setpoint_auth_t>(MakeTestMessage<setpoint_t>());
}
template <>
inline pose_auth_t MakeTestMessage<pose_auth_t>() {
  return MakeSealedTestMessage<pose_auth_t>(MakeTestMessage<pose_t>());
}
template <>
inline force_estimate_auth_t MakeTestMessage<force_estimate_auth_t>() {
  return MakeSealedTestMessage<force_estimate_auth_t>(MakeTestMessage<force_estimate_t>());
}
// The N-arm twins carry a counted message (n = 3): their length check walks it.
template <>
inline motor_command_n_auth_t MakeTestMessage<motor_command_n_auth_t>() {
  return MakeSealedTestMessage<motor_command_n_auth_t>(MakeTestMessage<motor_command_n_t>());
}
template <>
inline force_estimate_n_auth_t MakeTestMessage<force_estimate_n_auth_t>() {
  return MakeSealedTestMessage<force_estimate_n_auth_t>(MakeTestMessage<force_estimate_n_t>());
}

}  // namespace birotor::transport_test
