// One publisher per channel (seq_stream_lock.h, issue 37): a stream's seq
// and stamp advance at its plausible rate, drops stay in the stream, a
// copied seq that jumps ahead or a stamp ahead of the receiver's time is a
// second stream (a conflict: both refused until one is silent for the
// hold), a silent stream relocks, and seq wraps.
#include "controller/seq_stream_lock.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace birotor {
namespace {

using Verdict = SeqStreamLock::Verdict;

// The ESCs' rule: MOTOR_COMMAND at 500 Hz nominal, 750 Hz plausible.
SeqStreamLockParams CommandStream() {
  SeqStreamLockParams p;
  p.max_rate_hz = 750.0;
  p.conflict_hold_s = 0.1;
  p.silence_s = 0.1;
  return p;
}

uint64_t Digest(double a) { return PayloadDigest(&a, 1); }

TEST(SeqStreamLockTest, TenPercentDropsAtOneKilohertzStayInTheStream) {
  SeqStreamLockParams p;
  p.max_rate_hz = 1500.0;  // FORCE: 1 kHz nominal
  SeqStreamLock lock(p);
  uint32_t lcg = 12345;  // drops drawn by a fixed LCG (Numerical Recipes constants)
  int64_t sent = 0, dropped = 0, in_stream = 0;
  for (int32_t seq = 0; seq < 10000; ++seq) {
    lcg = lcg * 1664525u + 1013904223u;
    const int64_t t_us = 1000 * static_cast<int64_t>(seq);
    ++sent;
    if (seq > 0 && (lcg >> 8) % 10 == 0) {
      ++dropped;
      continue;
    }
    const Verdict v = lock.Admit(seq, t_us, Digest(seq), t_us + 300);  // 0.3 ms latency
    if (v == Verdict::kInStream) ++in_stream;
  }
  EXPECT_NEAR(static_cast<double>(dropped) / sent, 0.1, 0.01);
  EXPECT_EQ(in_stream, sent - dropped - 1);  // every one after the lock
  EXPECT_EQ(lock.foreign(), 0);
  EXPECT_EQ(lock.conflicts(), 0);
}

TEST(SeqStreamLockTest, CopiedSeqAheadIsAConflictBothRefusedUntilTheHold) {
  // Issue 37 item 1: the controller's stream at 500 Hz; a peer continues its
  // seq +50, stamped 0.2 s ahead, at 500 Hz.
  SeqStreamLock lock(CommandStream());
  int64_t t = 0;
  int32_t seq = 100;
  EXPECT_EQ(lock.Admit(seq, t, Digest(1), t), Verdict::kLocked);
  for (int i = 0; i < 10; ++i) {
    t += 2000;
    EXPECT_EQ(lock.Admit(++seq, t, Digest(1), t), Verdict::kInStream);
  }
  // A step of 50 after 1 ms: above 1 + 750 x 0.001 x 1.5 + 3 = 5.1.
  EXPECT_EQ(lock.Admit(seq + 50, t + 1000 + 200000, Digest(2), t + 1000), Verdict::kForeign);
  EXPECT_TRUE(lock.InConflict(t + 1000));
  for (int i = 0; i < 50; ++i) {  // 0.1 s of both
    t += 2000;
    EXPECT_EQ(lock.Admit(++seq, t, Digest(1), t), Verdict::kHeld);
    EXPECT_EQ(lock.Admit(seq + 50, t + 1000 + 200000, Digest(2), t + 1000), Verdict::kForeign);
  }
  EXPECT_EQ(lock.foreign(), 51);
  EXPECT_EQ(lock.held(), 50);
  EXPECT_EQ(lock.conflicts(), 1);
  // The peer stops; the real stream is refused until the peer has been
  // silent for the hold (0.1 s), then in stream again.
  const int64_t last_foreign = t + 1000;
  while (t + 2000 <= last_foreign + 100000) {
    t += 2000;
    EXPECT_EQ(lock.Admit(++seq, t, Digest(1), t), Verdict::kHeld);
  }
  t += 2000;
  EXPECT_FALSE(lock.InConflict(t));
  EXPECT_EQ(lock.Admit(++seq, t, Digest(1), t), Verdict::kInStream);
  EXPECT_EQ(lock.relocks(), 0);
}

TEST(SeqStreamLockTest, StampAheadOfTheReceiversTimeIsAnotherStream) {
  SeqStreamLock lock(CommandStream());
  EXPECT_EQ(lock.Admit(1, 0, Digest(1), 0), Verdict::kLocked);
  // Seq step 1, but the stamp 0.06 s ahead after 2 ms: above dt + 0.05 s.
  EXPECT_EQ(lock.Admit(2, 62000, Digest(1), 2000), Verdict::kForeign);
  // ... and a stamp going back.
  EXPECT_EQ(lock.Admit(2, -1000, Digest(1), 2500), Verdict::kForeign);
  EXPECT_EQ(lock.conflicts(), 1);
}

TEST(SeqStreamLockTest, NewestSeqWithAnotherPayloadIsAConflictAnExactResendIsNot) {
  SeqStreamLock lock(CommandStream());
  EXPECT_EQ(lock.Admit(7, 1000, Digest(700.0), 1000), Verdict::kLocked);
  EXPECT_EQ(lock.Admit(7, 1000, Digest(700.0), 1500), Verdict::kDuplicate);
  EXPECT_EQ(lock.conflicts(), 0);
  EXPECT_EQ(lock.Admit(7, 1000, Digest(0.0), 1600), Verdict::kForeign);
  EXPECT_EQ(lock.conflicts(), 1);
}

TEST(SeqStreamLockTest, SilentStreamRelocksOnARestartedPublisher) {
  SeqStreamLock lock(CommandStream());  // silence_s 0.1
  EXPECT_EQ(lock.Admit(500, 0, Digest(1), 0), Verdict::kLocked);
  EXPECT_EQ(lock.Admit(501, 2000, Digest(1), 2000), Verdict::kInStream);
  // Restarted at seq 0 after 0.1 s + 1 us of silence.
  EXPECT_EQ(lock.Admit(0, 102001, Digest(1), 102001), Verdict::kLocked);
  EXPECT_EQ(lock.relocks(), 1);
  EXPECT_EQ(lock.Admit(1, 104001, Digest(1), 104001), Verdict::kInStream);
  EXPECT_EQ(lock.conflicts(), 0);
}

TEST(SeqStreamLockTest, SeqWrapsAround) {
  SeqStreamLock lock(CommandStream());
  const int32_t max = std::numeric_limits<int32_t>::max();
  EXPECT_EQ(lock.Admit(max, 0, Digest(1), 0), Verdict::kLocked);
  EXPECT_EQ(lock.Admit(std::numeric_limits<int32_t>::min(), 2000, Digest(1), 2000), Verdict::kInStream);
  EXPECT_EQ(lock.Admit(std::numeric_limits<int32_t>::min() + 2, 6000, Digest(1), 6000), Verdict::kInStream);
}

}  // namespace
}  // namespace birotor
