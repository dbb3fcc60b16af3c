// The review page's headline: what a reader must see without zooming (which
// rotor failed and when, the max tilt, the altitude loss, whether the flight
// was lost, how much of FORCE was VALID, the controller's fallbacks), and the
// events drawn as markers through every chart. Computed from all samples of
// one FlightData; the definitions are in docs/review.md.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "review/flight_data.h"
#include "samples/flight_figures.h"
#include "samples/flight_verdict.h"

namespace birotor {

// A true thrust-scale change (TRUTH's thrust_scale[i] leaving its mean over
// the log's first kTrueFaultReferenceS by more than kTrueFaultScaleStep) is
// a fault of the flight, not of the estimate. The simulator's turbulence
// moves it by ~0.01 (turbulence_std; over a 15 s flight at 1 kHz its
// excursions from a 0.5 s mean reach 0.055), a fault by 0.25 or more.
inline constexpr double kTrueFaultScaleStep = 0.1;   // [1]
inline constexpr double kTrueFaultReferenceS = 0.5;  // [s]
// The VALID share is highlighted below this, or when MODEL_MISMATCH rose [1].
inline constexpr double kValidShareAlarm = 0.5;
// Rises listed per event kind; the count covers every one.
inline constexpr size_t kMaxListedRises = 8;

// One marked moment of the flight [s on the log's time axis].
struct FlightEvent {
  double t_s = 0.0;
  std::string kind;   // "fault" (estimator), "true fault" (TRUTH), "mismatch", "fallback", "reset", "lost"
  std::string label;  // e.g. "ROTOR2_FAULT", "rotor 2 thrust 1.00 -> 0.75"
};

struct FlightHeadline {
  // The shared verdict (samples/flight_verdict.h) on TRUTH, else POSE, against
  // SETPOINT's altitude; verdict_source "" when the log has no position.
  FlightVerdict verdict;
  std::string verdict_source;
  double lost_at_s = -1.0;      // first sample at which the verdict said lost; -1: kept
  int64_t force_estimates = 0;  // FORCE messages
  int64_t valid_estimates = 0;  // of them with VALID set
  bool has_truth = false;
  bool has_command = false;
  double first_valid_s = -1.0;  // first FORCE with VALID; -1 without
  // The flight's figures by the one definition (samples/flight_figures.h):
  // RMS position error and max tilt (with TRUTH), fallbacks as the controller
  // counts them (in every mode), MPC fallback periods.
  FlightFigureValues figures;
  int64_t fallbacks = 0;                     // the same rule on the MOTOR_COMMAND table (equal to figures.fallbacks)
  double force_used_s = -1.0;                // first force-feedback-mode command flown on FORCE; -1 without
  int64_t commands = 0;                      // MOTOR_COMMAND messages
  int64_t fallback_commands = 0;             // of them with FALLBACK_ACTIVE
  double startup_reset_s = -1.0;             // FILTER_RESET on the first FORCE (the start-up reset); -1 without
  int64_t mismatch_rises = 0;                // rises of MODEL_MISMATCH
  int64_t rotor_fault_rises[kMaxArms] = {};  // rises of ROTOR<i>_FAULT (rotor_count of them)
  std::vector<FlightEvent> events;           // every event, in time order
};

FlightHeadline ComputeHeadline(const FlightData& data);

// The verdict table: a column per log (logs[k] with headlines[k]), a row per
// question: lost, rotor faults (estimator and truth), max tilt, altitude
// loss, FORCE VALID share, fallbacks, filter resets after the start.
std::string HeadlineTableHtml(const std::vector<const FlightData*>& logs, const std::vector<FlightHeadline>& headlines);

// "headline: lost no; rotor faults ROTOR2_FAULT at 5.015 s; ..." for a terminal.
std::string HeadlineText(const FlightHeadline& headline);

}  // namespace birotor
