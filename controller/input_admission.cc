#include "controller/input_admission.h"

#include "numerics/time_units.h"

namespace birotor {

bool AdmitToStream(const SupervisionParams& s, const StreamMessage& message, bool valid, int64_t now_us,
                   SeqStreamLock* lock, ControllerInputCounters* counters) {
  ++counters->received;
  if (!valid) {
    ++counters->rejected_invalid;
    return false;
  }
  const double age_s = ElapsedSeconds(now_us, message.utime);
  if (-age_s > s.clock_future_window_s) {
    ++counters->rejected_future;
    return false;
  }
  if (age_s > s.clock_past_window_s) {
    ++counters->rejected_past;
    return false;
  }
  if (lock == nullptr) return true;
  switch (lock->Admit(message.seq, message.utime, message.digest, now_us)) {
    case SeqStreamLock::Verdict::kLocked:
    case SeqStreamLock::Verdict::kInStream:
      return true;
    case SeqStreamLock::Verdict::kDuplicate:
      ++counters->rejected_out_of_order;
      return false;
    case SeqStreamLock::Verdict::kForeign:
    case SeqStreamLock::Verdict::kHeld:
      ++counters->rejected_foreign;
      return false;
  }
  return false;
}

bool AcceptNewest(int64_t utime, ControllerInputCounters* counters) {
  if (counters->last_utime >= 0 && utime <= counters->last_utime) {
    ++counters->rejected_out_of_order;
    return false;
  }
  ++counters->accepted;
  counters->last_utime = utime;
  return true;
}

SeqStreamLockParams StreamLockParams(const SupervisionParams& s, double max_rate_hz) {
  SeqStreamLockParams params;
  params.max_rate_hz = max_rate_hz;
  params.rate_margin = s.stream_rate_margin;
  params.seq_slack = s.stream_seq_slack;
  params.stamp_slack_s = s.stream_stamp_slack_s;
  params.silence_s = s.stream_silence_s;
  params.conflict_hold_s = s.conflict_hold_s;
  return params;
}

}  // namespace birotor
