// How well a closed-loop flight held its reference (birotor-eval --control):
// RMS position error over the flight, and measured from the event (the
// fault; without one the lift-off, or the start) over a window: the peak
// tilt, the altitude deviation in both directions, the time back within a
// tolerance, and for a flight that comes down, the speed at touchdown. And
// the comparison of nominal and force feedback over seeds (issue 25).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "evaluation/closed_loop.h"
#include "samples/flight_verdict.h"

namespace birotor {

struct ControlMetricsOptions {
  // "Back" means the position error stays within this for the rest of the run [m].
  double return_tolerance_m = 0.05;
  // Peak tilt and altitude deviation are taken over [event, event + window_s] [s].
  double window_s = 3.0;
};

struct ControlMetrics {
  int64_t samples = 0;
  double rms_position_error_m = 0;  // the flight's RMS: samples/flight_figures.h, docs/review.md [m]
  double max_position_error_m = 0;  // [m]
  double peak_tilt_rad = 0;         // max |phi| over the whole run [rad]
  // From the event (first thrust step; else the lift-off; else the start):
  double fault_time_s = 0;               // event time from the start [s]
  double fault_peak_tilt_rad = 0;        // max |phi| in the window [rad]
  double peak_altitude_deviation_m = 0;  // max |z - z_ref| in the window [m]
  double peak_altitude_loss_m = 0;       // max(z_ref - z, 0) from the event to the end [m]
  // Time from the event until the error is within return_tolerance_m for
  // good: 0 if it never left; NaN if it is still outside at the end [s].
  double return_time_s = 0;
  bool crashed = false;  // peak altitude loss of 0.5 m or more
  // The flight came down on the ground after the event: the sink rate just
  // before contact [m/s] and the peak |tilt| until then [rad]; NaN otherwise.
  double touchdown_speed_m_s = 0;
  double tilt_before_touchdown_rad = 0;
  // At that contact: |tilt| [rad], |pitch rate| [rad/s], and the downward
  // speed of the lower tip (rigid arms: z_dot -+ L cos(phi) phi_dot, the tip
  // L |sin(phi)| below the body) [m/s]; NaN without a touchdown. A flare
  // (controller/rotor_allocation.h) trades these for the body's speed.
  double tilt_at_touchdown_rad = 0;
  double pitch_rate_at_touchdown_rad_s = 0;
  double tip_touchdown_speed_m_s = 0;
  // Kept or lost, by the one definition every program shares
  // (samples/flight_verdict.h), over the whole flight against the reference.
  FlightVerdict verdict;
};

ControlMetrics EvaluateControl(const ClosedLoopRun& run, const ControlMetricsOptions& options = {});

// The three compared figures (issue 25): RMS position, fault-relative peak
// tilt, altitude deviation.
struct ControlFigures {
  double rms_m = 0, tilt_rad = 0, altitude_m = 0;
};
ControlFigures FiguresOf(const ControlMetrics& m);

// Nominal and force feedback flown on the same seeds.
struct ControlComparison {
  int seeds = 0;
  ControlFigures nominal_median, feedback_median;
  // max over seeds of (force feedback / nominal) per figure [1].
  ControlFigures worst_ratio;
  int worst_seed[3] = {0, 0, 0};  // the seed of each worst ratio
  // Medians within 5 % of nominal and no seed worse by more than 25 %.
  bool met = false;
};
// nominal[k] and feedback[k] are seed k's figures.
ControlComparison CompareControl(const std::vector<ControlFigures>& nominal,
                                 const std::vector<ControlFigures>& feedback, const std::vector<int>& seeds);

// Markdown table of the control figures: one header, one row per (scenario, mode).
std::string ControlTableHeader();
std::string ControlTableRow(const std::string& scenario, const std::string& mode, const ControlMetrics& metrics,
                            const ClosedLoopRun& run);
// Markdown table of the comparison over seeds: one row per case.
std::string ComparisonTableHeader();
std::string ComparisonTableRow(const std::string& name, const ControlComparison& c);

}  // namespace birotor
