#include "controller/setpoint_publisher_lock.h"

#include <algorithm>

#include "numerics/time_units.h"

namespace birotor {

bool SetpointPublisherLock::SilentFor(int64_t arrival_us, int64_t now_us) const {
  return ElapsedSeconds(now_us, arrival_us) > rule_.conflict_hold_s;
}

bool SetpointPublisherLock::Continues(const Track& track, int32_t seq, int64_t utime, int64_t now_us) const {
  // One publisher sends at most max_rate_hz: in dt its seq moves on by
  // 1 .. 1 + max_rate dt (1 + margin) + slack (wrapping int32) and its
  // stamp by at most dt + slack (its clock runs as ours; a stamp that does
  // not advance is the order check's to refuse).
  const double dt_s = std::max(0.0, ElapsedSeconds(now_us, track.arrival_us));
  const int32_t seq_step = static_cast<int32_t>(static_cast<uint32_t>(seq) - static_cast<uint32_t>(track.seq));
  const double max_seq_step = 1.0 + rule_.max_rate_hz * dt_s * (1.0 + rule_.rate_margin) + rule_.seq_slack;
  const double stamp_advance_s = ElapsedSeconds(utime, track.utime);
  return seq_step >= 1 && seq_step <= max_seq_step && stamp_advance_s <= dt_s + rule_.stamp_slack_s;
}

bool SetpointPublisherLock::InConflict(int64_t now_us) const {
  return locked_ && foreign_heard_ && !SilentFor(foreign_arrival_us_, now_us) && !SilentFor(track_.arrival_us, now_us);
}

PublisherVerdict SetpointPublisherLock::Offer(int32_t seq, int64_t utime, int64_t now_us) {
  const Track message{seq, utime, now_us};
  if (locked_ && Continues(track_, seq, utime, now_us)) {
    track_ = message;
    return InConflict(now_us) ? PublisherVerdict::kConflict : PublisherVerdict::kLocked;
  }
  if (!locked_ || SilentFor(track_.arrival_us, now_us)) {
    // The first publisher, or the locked one gone quiet: this one is locked.
    locked_ = true;
    track_ = message;
    foreign_heard_ = false;
    return PublisherVerdict::kLocked;
  }
  // A second publisher while the locked one is alive (a repeated or
  // stepped-back seq included: one publisher never sends them).
  if (!InConflict(now_us)) ++conflicts_;
  foreign_heard_ = true;
  foreign_arrival_us_ = now_us;
  return PublisherVerdict::kConflict;
}

}  // namespace birotor
