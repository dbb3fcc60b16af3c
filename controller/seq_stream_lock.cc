#include "controller/seq_stream_lock.h"

#include <cstring>

#include "numerics/time_units.h"

namespace birotor {

uint64_t PayloadDigest(const double* values, int count) {
  uint64_t hash = 14695981039346656037ULL;  // FNV-1a 64-bit offset basis
  for (int i = 0; i < count; ++i) {
    unsigned char bytes[sizeof(double)];
    std::memcpy(bytes, &values[i], sizeof(double));
    for (unsigned char b : bytes) hash = (hash ^ b) * 1099511628211ULL;  // FNV prime
  }
  return hash;
}

bool SeqStreamLock::Follows(int32_t seq, int64_t utime, double dt_s) const {
  // Wrapping difference: int32 seq counters wrap around.
  const int32_t step = static_cast<int32_t>(static_cast<uint32_t>(seq) - static_cast<uint32_t>(last_seq_));
  const double max_step = 1.0 + params_.max_rate_hz * dt_s * (1.0 + params_.rate_margin) + params_.seq_slack;
  // In seconds: a wild stamp must not overflow the subtraction.
  const double stamp_advance_s = ElapsedSeconds(utime, last_utime_);
  return step >= 1 && step <= max_step && stamp_advance_s >= 0.0 && stamp_advance_s <= dt_s + params_.stamp_slack_s;
}

void SeqStreamLock::ResolveConflict(int64_t now_us) {
  if (!conflict_) return;
  if (ElapsedSeconds(now_us, last_foreign_us_) > params_.conflict_hold_s) conflict_ = false;
  if (ElapsedSeconds(now_us, last_in_stream_us_) > params_.conflict_hold_s) {
    // The locked stream went silent: the next message locks anew.
    conflict_ = false;
    locked_ = false;
  }
}

void SeqStreamLock::Lock(int32_t seq, int64_t utime, uint64_t digest, int64_t now_us) {
  ++locks_;
  locked_ = true;
  conflict_ = false;
  last_seq_ = seq;
  last_utime_ = utime;
  last_digest_ = digest;
  last_in_stream_us_ = now_us;
}

SeqStreamLock::Verdict SeqStreamLock::Admit(int32_t seq, int64_t utime, uint64_t digest, int64_t now_us) {
  ResolveConflict(now_us);
  const double dt_s = ElapsedSeconds(now_us, last_in_stream_us_);
  if (!locked_ || dt_s > params_.silence_s) {
    Lock(seq, utime, digest, now_us);
    return Verdict::kLocked;
  }
  if (seq == last_seq_ && utime == last_utime_ && digest == last_digest_) return Verdict::kDuplicate;
  if (Follows(seq, utime, dt_s > 0.0 ? dt_s : 0.0)) {
    last_seq_ = seq;
    last_utime_ = utime;
    last_digest_ = digest;
    last_in_stream_us_ = now_us;
    if (!conflict_ || !params_.refuse_locked_in_conflict) return Verdict::kInStream;
    ++held_;
    return Verdict::kHeld;
  }
  if (!conflict_) ++conflicts_;
  conflict_ = true;
  ++foreign_;
  last_foreign_us_ = now_us;
  return Verdict::kForeign;
}

bool SeqStreamLock::InConflict(int64_t now_us) const {
  return conflict_ && ElapsedSeconds(now_us, last_foreign_us_) <= params_.conflict_hold_s &&
         ElapsedSeconds(now_us, last_in_stream_us_) <= params_.conflict_hold_s;
}

}  // namespace birotor
