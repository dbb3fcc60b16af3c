// Which SETPOINT publisher the controller listens to (issue 37): the first
// seq stream is locked; a message continues it when its seq and stamp
// advance as one publisher's can in the time since its last message. A
// second publisher while the locked one is alive is a conflict: both are
// refused until one of them has been silent for conflict_hold_s. Sequence
// numbers and stamps are not authentication: this holds the vehicle still
// when two publishers disagree, it cannot tell which one is genuine.
// No allocation, no throw.
#pragma once

#include <cstdint>

namespace birotor {

// The lock's rule (SetpointParams lock_* and conflict_hold_s).
struct PublisherLockRule {
  double max_rate_hz = 500.0;   // fastest plausible publisher [Hz]
  double rate_margin = 0.5;     // seq step allowed: 1 + max_rate_hz dt (1 + margin) + seq_slack
  double seq_slack = 2.0;       // [messages]
  double stamp_slack_s = 0.02;  // stamp advance allowed: arrival interval + this [s]
  double conflict_hold_s =
      1.0;  // a publisher silent this long ends a conflict; the locked one silent this long frees the lock [s]
};

// What the lock says of one message.
enum class PublisherVerdict {
  kLocked,    // from the locked publisher, no conflict: go on with the other checks
  kConflict,  // refused: a second publisher is (or was just) talking
};

class SetpointPublisherLock {
 public:
  explicit SetpointPublisherLock(const PublisherLockRule& rule) : rule_(rule) {}

  // One message with the publisher's seq and stamp [us], arrived at the
  // controller's clock now_us [us].
  PublisherVerdict Offer(int32_t seq, int64_t utime, int64_t now_us);
  // True while both publishers are refused (the reference holds).
  bool InConflict(int64_t now_us) const;

  int64_t conflicts() const { return conflicts_; }  // entries into a conflict

 private:
  // The last message of one publisher.
  struct Track {
    int32_t seq = 0;
    int64_t utime = 0;
    int64_t arrival_us = 0;
  };
  // True when (seq, utime) arriving at now_us can follow track's last message.
  bool Continues(const Track& track, int32_t seq, int64_t utime, int64_t now_us) const;
  bool SilentFor(int64_t arrival_us, int64_t now_us) const;

  PublisherLockRule rule_;
  bool locked_ = false;
  Track track_;
  bool foreign_heard_ = false;
  int64_t foreign_arrival_us_ = 0;  // newest message not from the locked publisher
  int64_t conflicts_ = 0;
};

}  // namespace birotor
