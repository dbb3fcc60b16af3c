// The checks every controller input passes (issue 23, issue 37), in two
// stages so that the POSE gate can sit between them: the stream stage
// (plausible values, stamp within the clock windows, in the locked seq
// stream at a plausible rate) and the newest stage (newer than the newest
// accepted). Each refusal is counted once. No allocation.
#pragma once

#include <cstdint>

#include "controller/controller_params.h"
#include "controller/seq_stream_lock.h"
#include "samples/samples.h"

namespace birotor {

// Counters of one input since start-up.
struct ControllerInputCounters {
  int64_t received = 0;
  int64_t accepted = 0;
  int64_t rejected_invalid = 0;       // non-finite or implausible fields (FORCE: scale outside the band)
  int64_t rejected_out_of_order = 0;  // utime not newer than the newest accepted, or an exact re-send
  int64_t rejected_future = 0;        // stamp ahead of the clock by more than clock_future_window_s
  int64_t rejected_past = 0;          // stamp behind the clock by more than clock_past_window_s
  // FORCE, POSE: a second seq stream's message, or the locked stream's while
  // both are refused in a conflict (SeqStreamLock kForeign, kHeld).
  int64_t rejected_foreign = 0;
  int64_t rejected_gate = 0;  // POSE outside the innovation gate
  int64_t last_utime = -1;    // newest accepted [us]; -1 if none
};

// One input message's stream identity: seq, stamp [us], payload digest
// (PayloadDigest of its values).
struct StreamMessage {
  int32_t seq = 0;
  int64_t utime = 0;
  uint64_t digest = 0;
};

// Stage 1 at the controller's clock now_us [us]: counts the message as
// received; true when it is valid, within the clock windows and (lock not
// null) admitted by the stream lock.
bool AdmitToStream(const SupervisionParams& s, const StreamMessage& message, bool valid, int64_t now_us,
                   SeqStreamLock* lock, ControllerInputCounters* counters);
// Stage 2: true (accepted, the newest) when utime [us] is newer than the
// newest accepted.
bool AcceptNewest(int64_t utime, ControllerInputCounters* counters);

// Plausibility of a POSE and an IMU sample: finite, within the limits
// beyond which a sample is a corrupt one, not a state of this vehicle
// (|x|, |z| <= 1e4 m, |phi| <= 10 rad, |gyro| <= 100 rad/s, |accel| <= 1e3
// m/s^2), stamp not negative. Used by both controllers.
bool PlausiblePose(const PoseSample& sample);
bool PlausibleImu(const ImuSample& sample);

// The stream lock of an input publishing at most max_rate_hz [Hz].
SeqStreamLockParams StreamLockParams(const SupervisionParams& s, double max_rate_hz);

// The force recovery rule of both controllers: force feedback is flown only
// while the newest FORCE is VALID and at most force_timeout_s old, and after
// a healthy run of on-time samples (each stamped within force_timeout_s of
// the one before) has lasted force_recovery_s: a run of late FORCE (stamp
// gaps) is one fallback, not one per late sample. A FORCE stamped on time
// but delivered late falls back only while it is stale (its run goes on).
// No allocation.
class ForceRecovery {
 public:
  explicit ForceRecovery(const SupervisionParams& s) : timeout_s_(s.force_timeout_s), recovery_s_(s.force_recovery_s) {}

  // A FORCE the stream stage or the newest stage refused: an implausible one
  // ends the newest's health (the next plausible sample on time resumes the
  // run; an outlier does not restart it).
  void OnRefused(bool plausible) {
    if (!plausible) newest_healthy_ = false;
  }
  // An accepted FORCE stamped utime [us]; previous_utime: the newest accepted
  // before it [us] (-1: none); valid: its STATUS_VALID. Not VALID ends the
  // healthy run; a late one (or the first) starts a new one.
  void OnAccepted(int64_t utime, int64_t previous_utime, bool valid);
  // True when FORCE may be flown on at now_us [us] (controller clock),
  // newest_utime the newest accepted FORCE's stamp [us]. The caller adds its
  // own conditions (a conflict on the seq streams).
  bool Usable(int64_t now_us, int64_t newest_utime) const;

 private:
  double timeout_s_;
  double recovery_s_;
  bool newest_healthy_ = false;
  int64_t healthy_since_us_ = -1;  // start of the current healthy, on-time run; -1 while unhealthy
};

}  // namespace birotor
