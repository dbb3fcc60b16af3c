#include "controller/seq_stream_lock.h"

#include "numerics/time_units.h"

namespace birotor {

SeqStreamLock::Verdict SeqStreamLock::Admit(int32_t seq, int64_t now_us) {
  const bool silent = !locked_ || ElapsedSeconds(now_us, last_in_stream_us_) > params_.silence_s;
  if (silent) {
    if (locked_) ++relocks_;
    locked_ = true;
    last_seq_ = seq;
    last_in_stream_us_ = now_us;
    return Verdict::kLocked;
  }
  // Wrapping difference: int32 seq counters wrap around.
  const int32_t step = static_cast<int32_t>(static_cast<uint32_t>(seq) - static_cast<uint32_t>(last_seq_));
  if (step >= 1 && step <= params_.max_seq_step) {
    last_seq_ = seq;
    last_in_stream_us_ = now_us;
    return Verdict::kInStream;
  }
  if (step <= 0 && step > -params_.max_seq_step) return Verdict::kDuplicate;
  ++foreign_;
  last_foreign_us_ = now_us;
  return Verdict::kForeign;
}

bool SeqStreamLock::ConflictWithin(int64_t now_us, double hold_s) const {
  return foreign_ > 0 && ElapsedSeconds(now_us, last_foreign_us_) <= hold_s;
}

}  // namespace birotor
