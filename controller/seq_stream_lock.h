// One publisher at a time on a channel: the first seq stream heard is
// locked, and a message belongs to it when its seq follows the newest one by
// 1 to max_seq_step (wrapping). Anything else while the locked stream is
// alive is a second publisher: refused and counted (the ESCs' commander rule
// and the controller's FORCE/POSE conflict detection). After silence_s
// without a message of the locked stream, the next message locks anew (a
// restarted publisher). No allocation.
#pragma once

#include <cstdint>

namespace birotor {

struct SeqStreamLockParams {
  int32_t max_seq_step = 100;  // seq steps accepted within the stream (drops allowed) [1]
  double silence_s = 0.2;      // the locked stream is given up after this long without a message [s]
};

class SeqStreamLock {
 public:
  explicit SeqStreamLock(const SeqStreamLockParams& params) : params_(params) {}

  enum class Verdict {
    kLocked,     // first message, or the first after the stream went silent: the stream starts here
    kInStream,   // follows the locked stream
    kDuplicate,  // the newest seq again (or an older one within the step): not news, refused
    kForeign,    // another publisher's seq while the locked stream is alive: refused
  };
  // A message with seq arrived at now_us (the receiver's clock) [us].
  Verdict Admit(int32_t seq, int64_t now_us);

  // A foreign message arrived within hold_s [s] before now_us.
  bool ConflictWithin(int64_t now_us, double hold_s) const;
  int64_t foreign() const { return foreign_; }
  int64_t relocks() const { return relocks_; }  // locks after the first
  bool locked() const { return locked_; }

 private:
  SeqStreamLockParams params_;
  bool locked_ = false;
  int32_t last_seq_ = 0;
  int64_t last_in_stream_us_ = 0;
  int64_t last_foreign_us_ = 0;
  int64_t foreign_ = 0;
  int64_t relocks_ = 0;
};

}  // namespace birotor
