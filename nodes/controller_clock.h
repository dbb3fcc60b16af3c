// The controller daemons' own clock (birotor and N rotors): the host's
// steady clock put on the vehicle's time base when two different inputs
// agree on it, never moved by a later one except after a silence (a
// restarted vehicle clock, issue 37); and the fixed control-period grid with
// its loop-time ring for CONTROLLER_STATUS. No allocation, no throw.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "controller/controller_params.h"

namespace birotor {

// The inputs that may set the clock (POSE, IMU, FORCE or FORCE_N: the
// ControllerInput order of nodes/controller_service.h).
constexpr int kClockInputs = 3;

class ControllerClock {
 public:
  explicit ControllerClock(const SupervisionParams& supervision) : supervision_(supervision) {}

  // The clock for input (0 .. kClockInputs - 1) stamped utime [us] arriving
  // at host_us [us] (-1: not set yet). Set (and relatched after
  // kClockRelatchUs without an accepted input) only when two different
  // inputs agree on the vehicle time within clock_agreement_s; advanced,
  // never more than the future window at a time, to the earliest-arriving
  // input during the first kClockAcquireUs.
  int64_t ForInput(int input, int64_t utime, int64_t host_us);
  // Vehicle time at host_us: host time plus the offset; -1 before it is set.
  int64_t VehicleTimeUs(int64_t host_us) const { return set_ ? host_us + offset_us_ : -1; }
  // An input was accepted at host_us (the relatch watches the silence).
  void NoteAccepted(int64_t host_us) { last_accepted_host_us_ = host_us; }
  bool set() const { return set_; }
  int64_t relatches() const { return relatches_; }

  static constexpr int64_t kClockAcquireUs = 500000;   // the clock follows the earliest input this long [us]
  static constexpr int64_t kClockRelatchUs = 2000000;  // no input accepted this long: set again [us]

 private:
  SupervisionParams supervision_;
  bool set_ = false;
  int64_t offset_us_ = 0;
  int64_t set_host_us_ = 0;
  int64_t last_accepted_host_us_ = 0;
  int64_t relatches_ = 0;
  // Each input's newest offset candidate (utime - host time [us]) and its host time (-1: none).
  int64_t candidate_offset_us_[kClockInputs] = {0, 0, 0};
  int64_t candidate_host_us_[kClockInputs] = {-1, -1, -1};
};

// Control periods on a fixed grid of period_us of host time, whatever the
// inputs do, and the loop time of each period (a fixed ring; the newest win).
class ControlPeriodGrid {
 public:
  explicit ControlPeriodGrid(int64_t period_us) : period_us_(period_us) {}
  // Host time of the next period (0 before the first: at once).
  int64_t Next() const { return next_host_us_ < 0 ? 0 : next_host_us_; }
  // A period ran at host_us: the next on the grid; after a stall longer than
  // a period the grid starts again from now (no burst of catch-up commands).
  void Ran(int64_t host_us);
  // The period that started at host_us ended at done_us [us].
  void NoteLoopTime(int64_t host_us, int64_t done_us);
  // p99 and max of the loop times since the last call [us] (NaN: none); starts a new reporting period.
  void TakeLoopTimes(double* p99_us, double* max_us);

 private:
  static constexpr size_t kCapacity = 4096;
  int64_t period_us_;
  int64_t next_host_us_ = -1;
  std::array<double, kCapacity> loop_times_us_{};
  size_t count_ = 0;
};

}  // namespace birotor
