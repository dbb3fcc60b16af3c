// The ESCs' rule for external rotor commands (MOTOR_COMMAND of the birotor,
// MOTOR_COMMAND_N of a vehicle with N rotors), the contract's rule for any
// motor interface: one commander at a time (the first seq stream; another is
// counted and ignored until the first has been silent for the command
// timeout), stamps checked against the ESCs' clock (older than the timeout,
// not newer than the newest run, or later than kEscFutureWindowS: refused),
// a speed that is not finite or outside [0, omega_max] refused (the last
// good command is held, then the timeout spools the motors down). Used by
// Simulator and by the N-rotor ESC node. No allocation.
#pragma once

#include <cstdint>

#include "controller/seq_stream_lock.h"
#include "simulator/scenario.h"

namespace birotor {

// What the ESCs did with a command offered to them.
enum class EscVerdict {
  kAccepted,
  kForeign,     // a second commander's seq stream (a conflict): ignored
  kHeld,        // the locked commander's command during a conflict: ignored too (the last good one holds)
  kStale,       // stamp older than the command timeout, or not newer than the newest run
  kFuture,      // stamp ahead of the ESCs' clock by more than kEscFutureWindowS
  kOutOfRange,  // a speed not finite or outside [0, omega_max]: the last good one is held
};
struct EscCounters {
  int64_t received = 0, accepted = 0, foreign = 0, stale = 0, future = 0, out_of_range = 0;
  int64_t held = 0;       // the locked commander's commands refused during a conflict (kHeld)
  int64_t conflicts = 0;  // entries into a conflict between two commanders (SeqStreamLock)
};
// A command stamped later than the ESCs' clock plus this is refused [s]
// (the controller's clock runs on its host; a lagging simulator sees its
// stamps a little ahead).
inline constexpr double kEscFutureWindowS = 0.25;

class EscCommandRule {
 public:
  // esc: the commander lock's rates and slacks (scenario esc: section);
  // command_timeout_s: no command accepted this long: the motors spool down.
  EscCommandRule(const EscParams& esc, double command_timeout_s);

  // A command (seq, stamp utime [us], n speeds [rad/s]) arrived when the
  // ESCs' clock read now_us [us]; kAccepted: the caller runs it.
  EscVerdict Offer(int32_t seq, int64_t utime, const double* omega_cmd_rad_s, int n, double omega_max_rad_s,
                   int64_t now_us);
  // At the ESCs' clock now_us: true when no command was accepted for the
  // timeout (the motors spool down); counts each entry. The first call
  // starts the timeout (before any command the start state's speeds run).
  bool TimedOut(int64_t now_us);

  const EscCounters& counters() const { return counters_; }
  bool timed_out() const { return timed_out_; }
  int64_t timeouts() const { return timeouts_; }

 private:
  int64_t command_timeout_us_;
  SeqStreamLock commander_;
  EscCounters counters_;
  int64_t last_accepted_us_ = -1;      // ESCs' clock at the newest accepted command (or the start); -1 before
  int64_t newest_command_utime_ = -1;  // stamp of the newest accepted command; -1 before any
  bool timed_out_ = false;
  int64_t timeouts_ = 0;
};

}  // namespace birotor
