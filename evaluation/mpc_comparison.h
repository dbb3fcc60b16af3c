// The MPC comparison of birotor-eval --control --mpc (issue 21): per run the
// figures of the targets and the command checks (every command within
// [0, omega_max], every change within the MPC's rate limit), and per case the
// medians with their spread over the seeds for the force-feedback cascade and
// the MPC without and with the estimated efficiencies.
#pragma once

#include <string>
#include <vector>

#include "controller/controller_params.h"
#include "evaluation/closed_loop.h"
#include "evaluation/control_metrics.h"

namespace birotor {

struct MpcRunFigures {
  ControlFigures control;          // RMS, fault-relative peak tilt, altitude deviation
  double touchdown_speed_m_s = 0;  // NaN without a touchdown
  double tilt_before_touchdown_rad = 0;
  double tip_touchdown_speed_m_s = 0;  // the lower tip's (ControlMetrics); NaN without a touchdown
  int64_t commands_out_of_bounds = 0;  // outside [0, omega_max]
  int64_t commands_over_rate = 0;      // |change| > max_omega_rate_rad_s2 x period (+1e-9), first in flight exempt
  double max_command_change_rad_s = 0;
  int64_t solves = 0, fallbacks = 0;
  double solve_p99_s = 0;  // on the lock-step's clock (thread CPU time)
};

// Figures of one run; config is the controller's (bounds and rate limit).
MpcRunFigures MpcFiguresOf(const ClosedLoopRun& run, const ControlMetrics& metrics, const ControllerConfig& config);

// Markdown: one row per (case, mode) with the medians [min, max] over seeds.
std::string MpcComparisonHeader();
std::string MpcComparisonRow(const std::string& name, const std::string& mode, const std::vector<MpcRunFigures>& runs);

}  // namespace birotor
