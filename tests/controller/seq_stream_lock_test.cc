// One publisher per channel (seq_stream_lock.h): the first seq stream is
// locked, drops within max_seq_step follow it, another stream is foreign
// until the locked one has been silent for silence_s, and seq wraps.
#include "controller/seq_stream_lock.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace birotor {
namespace {

using Verdict = SeqStreamLock::Verdict;

TEST(SeqStreamLockTest, FirstStreamLockedSecondRefusedUntilSilence) {
  SeqStreamLock lock{SeqStreamLockParams()};  // max_seq_step 100, silence_s 0.2
  EXPECT_EQ(lock.Admit(10, 0), Verdict::kLocked);
  EXPECT_EQ(lock.Admit(11, 1000), Verdict::kInStream);
  EXPECT_EQ(lock.Admit(111, 2000), Verdict::kInStream);   // a drop of 99
  EXPECT_EQ(lock.Admit(5000, 3000), Verdict::kForeign);   // another publisher
  EXPECT_EQ(lock.Admit(111, 3500), Verdict::kDuplicate);  // the same seq again
  EXPECT_EQ(lock.Admit(50, 4000), Verdict::kDuplicate);   // behind, within the step
  EXPECT_TRUE(lock.ConflictWithin(3000 + 300000, 0.3));
  EXPECT_FALSE(lock.ConflictWithin(3000 + 300001, 0.3));
  EXPECT_EQ(lock.foreign(), 1);
  // The locked stream silent for more than 0.2 s: the next one locks.
  EXPECT_EQ(lock.Admit(5001, 2000 + 200001), Verdict::kLocked);
  EXPECT_EQ(lock.relocks(), 1);
  EXPECT_EQ(lock.Admit(112, 2000 + 200002), Verdict::kForeign);
}

TEST(SeqStreamLockTest, SeqWrapsAround) {
  SeqStreamLock lock{SeqStreamLockParams()};
  const int32_t max = std::numeric_limits<int32_t>::max();
  EXPECT_EQ(lock.Admit(max, 0), Verdict::kLocked);
  EXPECT_EQ(lock.Admit(std::numeric_limits<int32_t>::min(), 1000), Verdict::kInStream);
}

}  // namespace
}  // namespace birotor
