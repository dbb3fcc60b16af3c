#include "evaluation/mpc_comparison.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "numerics/percentile.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {

// "median [min, max]" of one figure over the runs (NaN values skipped).
template <typename Get>
std::string Spread(const std::vector<MpcRunFigures>& runs, Get get, const char* format) {
  std::vector<double> values;
  for (const MpcRunFigures& r : runs) {
    const double v = get(r);
    if (std::isfinite(v)) values.push_back(v);
  }
  if (values.empty()) return "-";
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  const double low = *lo, high = *hi;
  return fmt::format(fmt::runtime(std::string(format) + " [" + format + ", " + format + "]"), Percentile(values, 0.5),
                     low, high);
}

}  // namespace

MpcRunFigures MpcFiguresOf(const ClosedLoopRun& run, const ControlMetrics& metrics, const ControllerConfig& config) {
  MpcRunFigures out;
  out.control = FiguresOf(metrics);
  out.touchdown_speed_m_s = metrics.touchdown_speed_m_s;
  out.tilt_before_touchdown_rad = metrics.tilt_before_touchdown_rad;
  out.tip_touchdown_speed_m_s = metrics.tip_touchdown_speed_m_s;
  const double omega_max = config.vehicle.omega_max_rad_s;
  const double max_change = config.mpc.max_omega_rate_rad_s2 / CommandRateHz(config) + 1e-9;
  bool previous_in_flight = false;
  for (size_t k = 0; k < run.commands.size(); ++k) {
    const MotorCommand& c = run.commands[k];
    const bool in_flight = (c.status & kCommandNoPoseYet) == 0;
    for (int i = 0; i < kBirotorRotors; ++i) {
      if (!(c.omega_cmd_rad_s[i] >= 0.0 && c.omega_cmd_rad_s[i] <= omega_max)) ++out.commands_out_of_bounds;
      if (in_flight && previous_in_flight) {
        const double change = std::fabs(c.omega_cmd_rad_s[i] - run.commands[k - 1].omega_cmd_rad_s[i]);
        out.max_command_change_rad_s = std::max(out.max_command_change_rad_s, change);
        if (change > max_change) ++out.commands_over_rate;
      }
    }
    previous_in_flight = in_flight;
  }
  out.solves = run.mpc.solves;
  out.fallbacks = run.mpc.Fallbacks();
  out.solve_p99_s = run.mpc.solve_p99_s;
  return out;
}

std::string MpcComparisonHeader() {
  return "| case | mode | RMS position [m] | fault peak tilt [rad] | altitude deviation [m] | touchdown speed [m/s] | "
         "tilt before touchdown [rad] | lower tip at touchdown [m/s] | max command change [rad/s] | out of bounds / "
         "over "
         "rate | solve p99 [us] | fallbacks / solves |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
}

std::string MpcComparisonRow(const std::string& name, const std::string& mode, const std::vector<MpcRunFigures>& runs) {
  int64_t out_of_bounds = 0, over_rate = 0, fallbacks = 0, solves = 0;
  for (const MpcRunFigures& r : runs) {
    out_of_bounds += r.commands_out_of_bounds;
    over_rate += r.commands_over_rate;
    fallbacks += r.fallbacks;
    solves += r.solves;
  }
  const bool mpc = solves > 0;
  return fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} / {} | {} | {} |\n", name, mode,
                     Spread(
                         runs, [](const MpcRunFigures& r) { return r.control.rms_m; }, "{:.4f}"),
                     Spread(
                         runs, [](const MpcRunFigures& r) { return r.control.tilt_rad; }, "{:.4f}"),
                     Spread(
                         runs, [](const MpcRunFigures& r) { return r.control.altitude_m; }, "{:.4f}"),
                     Spread(
                         runs, [](const MpcRunFigures& r) { return r.touchdown_speed_m_s; }, "{:.2f}"),
                     Spread(
                         runs, [](const MpcRunFigures& r) { return r.tilt_before_touchdown_rad; }, "{:.3f}"),
                     Spread(
                         runs, [](const MpcRunFigures& r) { return r.tip_touchdown_speed_m_s; }, "{:.2f}"),
                     Spread(
                         runs, [](const MpcRunFigures& r) { return r.max_command_change_rad_s; }, "{:.0f}"),
                     out_of_bounds, mpc ? std::to_string(over_rate) : std::string("-"),
                     mpc ? Spread(
                               runs, [](const MpcRunFigures& r) { return 1e6 * r.solve_p99_s; }, "{:.0f}")
                         : std::string("-"),
                     mpc ? fmt::format("{} / {}", fallbacks, solves) : std::string("-"));
}

}  // namespace birotor
