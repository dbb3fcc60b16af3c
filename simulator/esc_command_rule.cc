#include "simulator/esc_command_rule.h"

#include "numerics/time_units.h"

namespace birotor {
namespace {

SeqStreamLockParams CommanderLock(const EscParams& esc, double command_timeout_s) {
  SeqStreamLockParams lock;
  lock.max_rate_hz = esc.command_max_rate_hz;
  lock.rate_margin = esc.rate_margin;
  lock.seq_slack = esc.seq_slack;
  lock.stamp_slack_s = esc.stamp_slack_s;
  lock.conflict_hold_s = esc.conflict_hold_s;
  lock.refuse_locked_in_conflict = !esc.follow_commander_in_conflict;
  lock.silence_s = command_timeout_s;
  return lock;
}

}  // namespace

EscCommandRule::EscCommandRule(const EscParams& esc, double command_timeout_s)
    : command_timeout_us_(SecondsToUtime(command_timeout_s)), commander_(CommanderLock(esc, command_timeout_s)) {}

EscVerdict EscCommandRule::Offer(int32_t seq, int64_t utime, const double* omega_cmd_rad_s, int n,
                                 double omega_max_rad_s, int64_t now_us) {
  EscCounters& c = counters_;
  ++c.received;
  if (utime > now_us + SecondsToUtime(kEscFutureWindowS)) {
    ++c.future;
    return EscVerdict::kFuture;
  }
  if (utime < now_us - command_timeout_us_ || (newest_command_utime_ >= 0 && utime <= newest_command_utime_)) {
    ++c.stale;
    return EscVerdict::kStale;
  }
  for (int i = 0; i < n; ++i) {
    if (!(omega_cmd_rad_s[i] >= 0.0 && omega_cmd_rad_s[i] <= omega_max_rad_s)) {
      ++c.out_of_range;
      return EscVerdict::kOutOfRange;
    }
  }
  const SeqStreamLock::Verdict verdict = commander_.Admit(seq, utime, PayloadDigest(omega_cmd_rad_s, n), now_us);
  c.conflicts = commander_.conflicts();
  switch (verdict) {
    case SeqStreamLock::Verdict::kForeign:
      ++c.foreign;
      return EscVerdict::kForeign;
    case SeqStreamLock::Verdict::kHeld:
      // Both commanders refused in a conflict: the last good command holds
      // until the command timeout.
      ++c.held;
      return EscVerdict::kHeld;
    case SeqStreamLock::Verdict::kDuplicate:
      ++c.stale;
      return EscVerdict::kStale;
    case SeqStreamLock::Verdict::kLocked:
    case SeqStreamLock::Verdict::kInStream:
      break;
  }
  ++c.accepted;
  newest_command_utime_ = utime;
  last_accepted_us_ = now_us;
  return EscVerdict::kAccepted;
}

bool EscCommandRule::TimedOut(int64_t now_us) {
  if (last_accepted_us_ < 0) last_accepted_us_ = now_us;  // the start state's speeds, for at most the timeout
  const bool timed_out = now_us - last_accepted_us_ > command_timeout_us_;
  if (timed_out && !timed_out_) ++timeouts_;
  timed_out_ = timed_out;
  return timed_out;
}

}  // namespace birotor
