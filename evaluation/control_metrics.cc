#include "evaluation/control_metrics.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace birotor {
namespace {

// Altitude loss at which the vehicle counts as crashed (issue 12) [m].
constexpr double kCrashAltitudeLossM = 0.5;

}  // namespace

ControlMetrics EvaluateControl(const ClosedLoopRun& run, const ControlMetricsOptions& options) {
  ControlMetrics m;
  if (run.samples.empty()) return m;
  const int64_t start_utime = run.samples.front().truth.utime;
  const int64_t fault_utime = run.fault_utime >= 0 ? run.fault_utime : start_utime;
  m.fault_time_s = 1e-6 * static_cast<double>(fault_utime - start_utime);
  double sum_squared = 0;
  int64_t last_outside_utime = -1;  // newest sample after the fault outside the tolerance
  for (const TrackedSample& s : run.samples) {
    const double dx = s.truth.x_m - s.reference_m.x();
    const double dz = s.truth.z_m - s.reference_m.y();
    const double error = std::hypot(dx, dz);
    sum_squared += error * error;
    m.max_position_error_m = std::max(m.max_position_error_m, error);
    m.peak_tilt_rad = std::max(m.peak_tilt_rad, std::fabs(s.truth.phi_rad));
    if (s.truth.utime < fault_utime) continue;
    m.peak_altitude_loss_m = std::max(m.peak_altitude_loss_m, -dz);
    if (error > options.return_tolerance_m) last_outside_utime = s.truth.utime;
  }
  m.samples = static_cast<int64_t>(run.samples.size());
  m.rms_position_error_m = std::sqrt(sum_squared / static_cast<double>(m.samples));
  if (last_outside_utime < 0) {
    m.return_time_s = 0;
  } else if (last_outside_utime == run.samples.back().truth.utime) {
    m.return_time_s = std::numeric_limits<double>::quiet_NaN();
  } else {
    m.return_time_s = 1e-6 * static_cast<double>(last_outside_utime - fault_utime);
  }
  m.crashed = m.peak_altitude_loss_m >= kCrashAltitudeLossM;
  return m;
}

std::string ControlTableHeader() {
  return "| scenario | controller | RMS position error [m] | peak tilt [rad] | fault at [s] | "
         "peak altitude loss [m] | back within 5 cm [s] | fallbacks | crashed |\n"
         "|---|---|---|---|---|---|---|---|---|\n";
}

std::string ControlTableRow(const std::string& scenario, const std::string& mode, const ControlMetrics& m,
                            const ClosedLoopRun& run) {
  const std::string back = std::isnan(m.return_time_s) ? "never" : fmt::format("{:.2f}", m.return_time_s);
  return fmt::format("| {} | {} | {:.4f} | {:.4f} | {:.2f} | {:.4f} | {} | {} | {} |\n", scenario, mode,
                     m.rms_position_error_m, m.peak_tilt_rad, m.fault_time_s, m.peak_altitude_loss_m, back,
                     run.controller.fallbacks, m.crashed ? "yes" : "no");
}

}  // namespace birotor
