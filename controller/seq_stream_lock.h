// One publisher at a time on a channel (issue 37): the first seq stream
// heard is locked, and a message belongs to it only when its seq and stamp
// advance at the publisher's plausible rate since the stream's last message
// (a copied seq that jumps ahead, or a stamp ahead of the receiver's time,
// is not this stream). Any other message while the locked stream is alive
// is a second stream: a CONFLICT, and both streams are refused until one of
// them has been silent for conflict_hold_s. After silence_s without a
// message of the locked stream the next message locks anew (a restarted
// publisher). Used by the ESCs' commander rule and the controller's FORCE
// and POSE. No allocation.
#pragma once

#include <cstdint>

namespace birotor {

struct SeqStreamLockParams {
  // Plausible rate: after receiver time dt [s] since the stream's last
  // message, a seq step above 1 + max_rate_hz dt (1 + rate_margin) + seq_slack
  // or a stamp advance above dt + stamp_slack_s is not this stream.
  double max_rate_hz = 1000.0;   // the publisher's highest expected rate [Hz]
  double rate_margin = 0.5;      // [1]
  double seq_slack = 3.0;        // seq steps beyond the rate (a burst after a stall) [1]
  double stamp_slack_s = 0.05;   // the stamp may run ahead of the receiver's time by this (latency jitter) [s]
  double silence_s = 0.2;        // the locked stream is given up after this long without a message [s]
  double conflict_hold_s = 0.3;  // both streams refused until one has been silent this long [s]
  // false: during a conflict the locked stream's in-stream messages are
  // still accepted (kInStream) and only the other stream is refused (the
  // ESCs' choice, EscParams::follow_commander_in_conflict).
  bool refuse_locked_in_conflict = true;
};

// FNV-1a over the bytes of a message's values: "the same payload" for the
// exact re-send test (a copy of the newest seq with another payload is a
// second stream).
uint64_t PayloadDigest(const double* values, int count);

class SeqStreamLock {
 public:
  explicit SeqStreamLock(const SeqStreamLockParams& params) : params_(params) {}

  enum class Verdict {
    kLocked,     // first message, or the first after the stream went silent: the stream starts here
    kInStream,   // follows the locked stream at a plausible rate: accepted
    kDuplicate,  // an exact re-send of the newest (seq, stamp and payload): not news, refused
    kForeign,    // a second stream while the locked one is alive: refused, a conflict
    kHeld,       // follows the locked stream during a conflict: refused too
  };
  // A message with seq, stamp utime [us] and payload digest arrived at now_us
  // (the receiver's clock) [us].
  Verdict Admit(int32_t seq, int64_t utime, uint64_t digest, int64_t now_us);

  // Both streams are being refused at now_us (a foreign message within
  // conflict_hold_s and the locked stream not silent that long).
  bool InConflict(int64_t now_us) const;
  int64_t foreign() const { return foreign_; }                     // messages of a second stream
  int64_t held() const { return held_; }                           // the locked stream's messages refused in a conflict
  int64_t conflicts() const { return conflicts_; }                 // entries into a conflict
  int64_t relocks() const { return locks_ > 1 ? locks_ - 1 : 0; }  // locks after the first
  bool locked() const { return locked_; }

 private:
  // Seq and stamp follow the locked stream after receiver time dt_s [s].
  bool Follows(int32_t seq, int64_t utime, double dt_s) const;
  // Ends a conflict whose foreign or locked stream has been silent for the hold.
  void ResolveConflict(int64_t now_us);
  void Lock(int32_t seq, int64_t utime, uint64_t digest, int64_t now_us);

  SeqStreamLockParams params_;
  bool locked_ = false;
  bool conflict_ = false;
  int32_t last_seq_ = 0;
  int64_t last_utime_ = 0;
  uint64_t last_digest_ = 0;
  int64_t last_in_stream_us_ = 0;
  int64_t last_foreign_us_ = 0;
  int64_t foreign_ = 0;
  int64_t held_ = 0;
  int64_t conflicts_ = 0;
  int64_t locks_ = 0;
};

}  // namespace birotor
