// The fixed-capacity FIFO of waiting samples (estimator/sample_queue.h):
// order, wrap-around, and the oldest handed back when full.
#include "estimator/sample_queue.h"

#include <gtest/gtest.h>

namespace birotor {
namespace {

TEST(SampleQueueTest, KeepsOrderAcrossTheWrapAndDropsTheOldestWhenFull) {
  SampleQueue<int, 3> queue;
  int dropped = -1;
  EXPECT_TRUE(queue.empty());
  EXPECT_FALSE(queue.push(1, &dropped));
  EXPECT_FALSE(queue.push(2, &dropped));
  EXPECT_FALSE(queue.push(3, &dropped));
  EXPECT_EQ(dropped, -1);
  EXPECT_EQ(queue.size(), 3);
  EXPECT_TRUE(queue.push(4, &dropped));  // full: 1 goes
  EXPECT_EQ(dropped, 1);
  EXPECT_EQ(queue.size(), 3);
  EXPECT_EQ(queue.front(), 2);
  queue.pop();
  EXPECT_FALSE(queue.push(5, &dropped));  // wraps in the ring
  for (int expected : {3, 4, 5}) {
    ASSERT_FALSE(queue.empty());
    EXPECT_EQ(queue.front(), expected);
    queue.pop();
  }
  EXPECT_TRUE(queue.empty());
}

}  // namespace
}  // namespace birotor
