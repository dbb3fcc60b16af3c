#include "evaluation/control_metrics.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "numerics/percentile.h"

namespace birotor {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Altitude loss at which the vehicle counts as crashed (issue 12) [m].
constexpr double kCrashAltitudeLossM = 0.5;
// Issue 25: medians within 5 %, no seed worse by more than 25 %.
constexpr double kMedianTolerance = 1.05;
constexpr double kSeedTolerance = 1.25;
// Figures below these are noise floors, not differences: a ratio is taken
// against at least this much [m, rad, m].
constexpr double kFloor[3] = {1e-3, 2e-3, 2e-3};
// A body within this of the support is on it: the simulator's contact is
// inelastic and the body may hop off it within the next truth sample
// (a 1 kHz truth misses the contact itself), so contact is the first sample
// this close, not the first exactly on the support [m].
constexpr double kContactToleranceM = 1e-3;

// The attitude at contact and the lower tip's downward speed: tip i is at
// z -+ L sin(phi) (rigid arms), so the lower one is on the side sign(phi)
// points down, moving at z_dot -+ L cos(phi) phi_dot.
void SetTouchdownAttitude(const TruthSample& truth, double arm_length_m, ControlMetrics* m) {
  const double side = truth.phi_rad >= 0.0 ? 1.0 : -1.0;
  const double tip_z_dot_m_s = truth.z_dot_m_s - side * arm_length_m * std::cos(truth.phi_rad) * truth.phi_dot_rad_s;
  m->tilt_at_touchdown_rad = std::fabs(truth.phi_rad);
  m->pitch_rate_at_touchdown_rad_s = std::fabs(truth.phi_dot_rad_s);
  m->tip_touchdown_speed_m_s = std::max(-tip_z_dot_m_s, 0.0);
}

}  // namespace

ControlMetrics EvaluateControl(const ClosedLoopRun& run, const ControlMetricsOptions& options) {
  ControlMetrics m;
  if (run.samples.empty()) return m;
  const int64_t start_utime = run.samples.front().truth.utime;
  const int64_t flight_utime = run.liftoff_utime >= 0 ? run.liftoff_utime : start_utime;
  const int64_t event_utime = run.fault_utime >= 0 ? run.fault_utime : flight_utime;
  const int64_t window_end_utime = event_utime + std::llround(options.window_s * 1e6);
  m.fault_time_s = 1e-6 * static_cast<double>(event_utime - start_utime);
  m.touchdown_speed_m_s = m.tilt_before_touchdown_rad = kNaN;
  m.tilt_at_touchdown_rad = m.pitch_rate_at_touchdown_rad_s = m.tip_touchdown_speed_m_s = kNaN;
  const double ground_z_m = run.ground_z_m;
  int64_t last_outside_utime = -1;  // newest sample after the event outside the tolerance
  double tilt_since_event = 0;
  const TrackedSample* previous = nullptr;
  FlightJudge judge;
  for (const TrackedSample& s : run.samples) {
    judge.Add(1e-6 * static_cast<double>(s.truth.utime - start_utime), s.truth.z_m, s.reference_m.y(), s.truth.phi_rad,
              s.truth.z_dot_m_s, run.has_ground ? ground_z_m : kNaN);
    const double dx = s.truth.x_m - s.reference_m.x();
    const double dz = s.truth.z_m - s.reference_m.y();
    const double error = std::hypot(dx, dz);
    const double tilt = std::fabs(s.truth.phi_rad);
    m.peak_tilt_rad = std::max(m.peak_tilt_rad, tilt);
    if (s.truth.utime >= flight_utime) {
      m.max_position_error_m = std::max(m.max_position_error_m, error);
    }
    if (s.truth.utime >= event_utime) {
      if (s.truth.utime <= window_end_utime) {
        m.fault_peak_tilt_rad = std::max(m.fault_peak_tilt_rad, tilt);
        m.peak_altitude_deviation_m = std::max(m.peak_altitude_deviation_m, std::fabs(dz));
      }
      m.peak_altitude_loss_m = std::max(m.peak_altitude_loss_m, -dz);
      if (error > options.return_tolerance_m) last_outside_utime = s.truth.utime;
      if (std::isnan(m.touchdown_speed_m_s)) {
        tilt_since_event = std::max(tilt_since_event, tilt);
        if (run.has_ground && run.fault_utime >= 0 && previous != nullptr &&
            previous->truth.z_m > ground_z_m + kContactToleranceM && s.truth.z_m <= ground_z_m + kContactToleranceM) {
          m.touchdown_speed_m_s = std::max(-previous->truth.z_dot_m_s, 0.0);
          m.tilt_before_touchdown_rad = tilt_since_event;
          SetTouchdownAttitude(previous->truth, run.arm_length_m, &m);
        }
      }
    }
    previous = &s;
  }
  m.samples = static_cast<int64_t>(run.samples.size());
  // The one definition of the flight's RMS (samples/flight_figures.h).
  m.rms_position_error_m = run.figures.Result().rms_position_error_m;
  if (last_outside_utime < 0) {
    m.return_time_s = 0;
  } else if (last_outside_utime == run.samples.back().truth.utime) {
    m.return_time_s = kNaN;
  } else {
    m.return_time_s = 1e-6 * static_cast<double>(last_outside_utime - event_utime);
  }
  m.crashed = m.peak_altitude_loss_m >= kCrashAltitudeLossM;
  m.verdict = judge.Result();
  return m;
}

ControlFigures FiguresOf(const ControlMetrics& m) {
  return ControlFigures{m.rms_position_error_m, m.fault_peak_tilt_rad, m.peak_altitude_deviation_m};
}

ControlComparison CompareControl(const std::vector<ControlFigures>& nominal,
                                 const std::vector<ControlFigures>& feedback, const std::vector<int>& seeds) {
  ControlComparison c;
  c.seeds = static_cast<int>(std::min(nominal.size(), feedback.size()));
  if (c.seeds == 0) return c;
  double ControlFigures::*fields[3] = {&ControlFigures::rms_m, &ControlFigures::tilt_rad, &ControlFigures::altitude_m};
  c.met = true;
  for (int f = 0; f < 3; ++f) {
    std::vector<double> n, b;
    double worst = -1;
    for (int k = 0; k < c.seeds; ++k) {
      n.push_back(nominal[k].*fields[f]);
      b.push_back(feedback[k].*fields[f]);
      const double ratio = feedback[k].*fields[f] / std::max(nominal[k].*fields[f], kFloor[f]);
      if (!(ratio <= worst)) {
        worst = ratio;
        c.worst_seed[f] = seeds[k];
      }
    }
    c.nominal_median.*fields[f] = Percentile(n, 0.5);
    c.feedback_median.*fields[f] = Percentile(b, 0.5);
    c.worst_ratio.*fields[f] = worst;
    const double median_nominal = std::max(c.nominal_median.*fields[f], kFloor[f]);
    c.met = c.met && c.feedback_median.*fields[f] <= kMedianTolerance * median_nominal && worst <= kSeedTolerance;
  }
  return c;
}

std::string ControlTableHeader() {
  return "| scenario | controller | RMS position error [m] | peak tilt [rad] | event at [s] | tilt after event [rad] "
         "| altitude deviation [m] | peak altitude loss [m] | back within 5 cm [s] | touchdown [m/s] | at touchdown: "
         "tilt [rad], pitch rate [rad/s], lower tip [m/s] | fallbacks | crashed |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
}

std::string ControlTableRow(const std::string& scenario, const std::string& mode, const ControlMetrics& m,
                            const ClosedLoopRun& run) {
  const std::string back = std::isnan(m.return_time_s) ? "never" : fmt::format("{:.2f}", m.return_time_s);
  const bool landed = !std::isnan(m.touchdown_speed_m_s);
  const std::string touchdown = landed ? fmt::format("{:.2f}", m.touchdown_speed_m_s) : "-";
  const std::string attitude = landed ? fmt::format("{:.3f}, {:.2f}, {:.2f}", m.tilt_at_touchdown_rad,
                                                    m.pitch_rate_at_touchdown_rad_s, m.tip_touchdown_speed_m_s)
                                      : "-";
  return fmt::format("| {} | {} | {:.4f} | {:.4f} | {:.2f} | {:.4f} | {:.4f} | {:.4f} | {} | {} | {} | {} | {} |\n",
                     scenario, mode, m.rms_position_error_m, m.peak_tilt_rad, m.fault_time_s, m.fault_peak_tilt_rad,
                     m.peak_altitude_deviation_m, m.peak_altitude_loss_m, back, touchdown, attitude,
                     run.controller.fallbacks, m.crashed ? "yes" : "no");
}

std::string ComparisonTableHeader() {
  return "| case | seeds | RMS position [m] nominal / FF | tilt after event [rad] nominal / FF | altitude deviation "
         "[m] "
         "nominal / FF | worst seed FF/nominal (RMS, tilt, altitude) | met |\n|---|---|---|---|---|---|---|\n";
}

std::string ComparisonTableRow(const std::string& name, const ControlComparison& c) {
  const ControlFigures& n = c.nominal_median;
  const ControlFigures& b = c.feedback_median;
  return fmt::format(
      "| {} | {} | {:.4f} / {:.4f} | {:.4f} / {:.4f} | {:.4f} / {:.4f} | {:.2f} (seed {}), {:.2f} (seed {}), {:.2f} "
      "(seed {}) | {} |\n",
      name, c.seeds, n.rms_m, b.rms_m, n.tilt_rad, b.tilt_rad, n.altitude_m, b.altitude_m, c.worst_ratio.rms_m,
      c.worst_seed[0], c.worst_ratio.tilt_rad, c.worst_seed[1], c.worst_ratio.altitude_m, c.worst_seed[2],
      c.met ? "yes" : "NO");
}

}  // namespace birotor
