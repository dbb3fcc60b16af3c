// The figures of one flight that birotor-sim --controller, birotor-eval
// --control and birotor-review print: the RMS position error, the max tilt,
// the controller's fallbacks and the MPC's fallback periods. One definition,
// fed the same message streams (the lock-step closed loop its samples, the
// review the log's messages), so one flight gets one number everywhere.
// The definitions, once, are in docs/review.md ("Flight figures").
#pragma once

#include <cstdint>
#include <string>

#include "samples/samples.h"
#include "samples/setpoint.h"

namespace birotor {

struct FlightFigureValues {
  // sqrt(mean |p - p_ref|^2) over the TRUTH samples from the first one in
  // motion (a body on its support is held still: the ground phase is not
  // flown), p_ref the newest SETPOINT propagated to the sample's time by its
  // feed-forward (p + v dt + a dt^2 / 2); NaN before any scored sample [m].
  double rms_position_error_m = 0.0;
  int64_t scored_samples = 0;
  double max_tilt_rad = 0.0;  // max |phi| over every TRUTH sample [rad]
  // Entries into MOTOR_COMMAND's FALLBACK_ACTIVE from a command without it,
  // the start counting as in the fallback and commands with NO_POSE_YET
  // skipped: the controller's own count (ControllerHealth::fallbacks) in
  // every mode (force feedback and mpc on FORCE; 0 when FORCE is not flown).
  int64_t fallbacks = 0;
  int64_t fallback_commands = 0;  // commands with FALLBACK_ACTIVE
  // Mode mpc: commands with MPC_FALLBACK (the solve failed, was late or bad),
  // the MPC's MpcStats::Fallbacks().
  int64_t mpc_fallbacks = 0;

  // "RMS position error 0.0123 m, max tilt 0.0456 rad, fallbacks 5, MPC
  // fallbacks 0": the one line the three programs print; "RMS position
  // error - (no SETPOINT)" when nothing was scored (a flight holding its
  // first POSE publishes no setpoint).
  std::string Line() const;
};

// The controller's fallback rule on one MOTOR_COMMAND status: true when this
// command enters the fallback. *in_fallback starts true (force feedback
// starts in the fallback, not counted) and carries the state.
bool EntersFallback(int32_t status, bool* in_fallback);

// Feed the streams in the order they were published (no allocation).
class FlightFigures {
 public:
  void AddSetpoint(const Setpoint& setpoint);
  void AddTruth(const TruthSample& truth);
  void AddCommand(int32_t status);
  FlightFigureValues Result() const;

 private:
  FlightFigureValues values_;
  Setpoint setpoint_;
  bool has_setpoint_ = false;
  bool in_motion_ = false;
  bool in_fallback_ = true;
  double sum_squared_m2_ = 0.0;
};

}  // namespace birotor
