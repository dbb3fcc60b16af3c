#include "nodes/controller_status_message.h"

#include <cmath>
#include <limits>

#include "numerics/time_units.h"
#include "samples/motor_command.h"

namespace birotor {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

void BuildControllerStatus(const VehicleController& controller, const ControllerStatusContext& context,
                           controller_status_t* message) {
  BuildControllerStatus(controller.health(), controller.config(), controller.setpoint(), controller.MpcStatistics(),
                        context, message);
}

void BuildControllerStatus(const ControllerHealth& h, const ControllerConfig& config, const SetpointInput& setpoint,
                           const MpcStats& mpc, const ControllerStatusContext& context, controller_status_t* message) {
  controller_status_t& m = *message;
  const int64_t now_us = context.now_us;
  m.utime = now_us;
  m.wall_utime = context.wall_utime;
  m.mode = config.model_predictive ? kModeMpc : config.force_feedback ? kModeForceFeedback : kModeNominal;
  m.status = context.last_status;
  m.fallbacks = h.fallbacks;
  m.descents = h.descents;
  m.commands = h.commands;
  m.saturated = h.saturated;
  auto age = [&](const ControllerInputCounters& c) {
    return c.last_utime < 0 || now_us < 0 ? kNaN : ElapsedSeconds(now_us, c.last_utime);
  };
  m.pose_age_s = age(h.pose);
  m.imu_age_s = age(h.imu);
  m.force_age_s = age(h.force);
  const ControllerInputCounters* counters[kControllerStatusInputs] = {&h.pose, &h.imu, &h.force};
  for (int i = 0; i < kControllerStatusInputs; ++i) {
    m.received[i] = counters[i]->received + context.decode_errors[i];
    m.decode_errors[i] = context.decode_errors[i];
    m.rejected_invalid[i] = counters[i]->rejected_invalid;
    m.rejected_out_of_order[i] = counters[i]->rejected_out_of_order;
    m.rejected_future[i] = counters[i]->rejected_future;
    m.rejected_past[i] = counters[i]->rejected_past;
    m.rejected_foreign[i] = counters[i]->rejected_foreign;
  }
  m.pose_rejected_gate = h.pose.rejected_gate;
  m.pose_gate_resets = h.pose_gate_resets;
  m.conflicts = h.conflicts;
  m.infeasible = h.infeasible;
  m.clock_relatches = context.clock_relatches;
  m.efficiency[0] = h.efficiency[0];
  m.efficiency[1] = h.efficiency[1];
  const SetpointCounters sc = setpoint.counters();
  m.setpoint_state = static_cast<int32_t>(setpoint.state());
  m.setpoint_age_s = setpoint.last_utime() < 0 || now_us < 0 ? kNaN : ElapsedSeconds(now_us, setpoint.last_utime());
  m.setpoint_received = sc.received + context.setpoint_decode_errors;
  m.setpoint_decode_errors = context.setpoint_decode_errors;
  m.setpoint_rejected_invalid = sc.rejected_invalid;
  m.setpoint_rejected_stamp = sc.rejected_stamp;
  m.setpoint_rejected_out_of_order = sc.rejected_out_of_order;
  m.setpoint_rejected_rate = sc.rejected_rate;
  m.setpoint_rejected_jump = sc.rejected_jump;
  m.setpoint_timeouts = sc.timeouts;
  m.loop_time_p99_us = context.loop_time_p99_us;
  m.loop_time_max_us = context.loop_time_max_us;
  const bool solved = mpc.solves > 0 && context.report_solve_times;
  m.mpc_solves = mpc.solves;
  m.mpc_fallbacks = mpc.Fallbacks();
  m.mpc_solve_p50_us = solved ? 1e6 * mpc.solve_p50_s : kNaN;
  m.mpc_solve_p99_us = solved ? 1e6 * mpc.solve_p99_s : kNaN;
  m.mpc_solve_max_us = solved ? 1e6 * mpc.solve_max_s : kNaN;
  m.mpc_iterations = mpc.last_iterations;
  m.mpc_max_iterations = mpc.max_iterations;
  m.udp_fragments_dropped = context.udp_fragments_dropped;
  m.udp_malformed_dropped = context.udp_malformed_dropped;
}

}  // namespace birotor
