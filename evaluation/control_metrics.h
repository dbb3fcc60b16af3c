// How well a closed-loop flight held its reference (birotor-eval --control):
// RMS position error, peak tilt, the altitude lost after a thrust fault and
// the time it took to come back within a tolerance of the reference.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "evaluation/closed_loop.h"

namespace birotor {

struct ControlMetricsOptions {
  // "Back" means the position error stays within this for the rest of the run [m].
  double return_tolerance_m = 0.05;
};

struct ControlMetrics {
  int64_t samples = 0;
  double rms_position_error_m = 0;  // sqrt(mean |p - p_ref|^2) over the whole run [m]
  double max_position_error_m = 0;  // [m]
  double peak_tilt_rad = 0;         // max |phi| over the whole run [rad]
  // From the fault (first thrust step; the start when the run has none, e.g.
  // density's initial thrust scale) to the end:
  double fault_time_s = 0;          // [s]
  double peak_altitude_loss_m = 0;  // max(z_ref - z, 0) [m]
  // Time from the fault until the error is within return_tolerance_m for
  // good: 0 if it never left; NaN if it is still outside at the end [s].
  double return_time_s = 0;
  bool crashed = false;  // peak altitude loss of 0.5 m or more
};

ControlMetrics EvaluateControl(const ClosedLoopRun& run, const ControlMetricsOptions& options = {});

// Markdown table of the control figures: one header, one row per (scenario, mode).
std::string ControlTableHeader();
std::string ControlTableRow(const std::string& scenario, const std::string& mode, const ControlMetrics& metrics,
                            const ClosedLoopRun& run);

}  // namespace birotor
