// ReplayGuard (security/replay_guard.h): a publisher's counter must rise;
// eight publishers are remembered, the least recently heard one gives way.
#include "security/replay_guard.h"

#include <gtest/gtest.h>

#include <set>

namespace birotor {
namespace {

TEST(ReplayGuardTest, ACounterMustRisePerPublisher) {
  ReplayGuard guard;
  EXPECT_TRUE(guard.Admit(11, 1));
  EXPECT_TRUE(guard.Admit(11, 2));
  EXPECT_TRUE(guard.Admit(11, 50));   // drops between are fine
  EXPECT_FALSE(guard.Admit(11, 50));  // the same message again
  EXPECT_FALSE(guard.Admit(11, 3));   // an older one
  EXPECT_TRUE(guard.Admit(22, 1));    // another publisher has its own counter
  EXPECT_TRUE(guard.Admit(11, 51));
}

TEST(ReplayGuardTest, TheLeastRecentlyHeardOfNinePublishersIsForgotten) {
  ReplayGuard guard;
  for (uint64_t p = 1; p <= ReplayGuard::kPublishers; ++p) EXPECT_TRUE(guard.Admit(p, 100));
  EXPECT_TRUE(guard.Admit(1, 101));  // publisher 1 heard again: 2 is now the oldest
  EXPECT_TRUE(guard.Admit(99, 5));   // a ninth takes publisher 2's slot
  EXPECT_FALSE(guard.Admit(1, 101));
  for (uint64_t p = 3; p <= ReplayGuard::kPublishers; ++p) EXPECT_FALSE(guard.Admit(p, 100));
  EXPECT_TRUE(guard.Admit(2, 100));  // forgotten: its old counter passes again (the stamp checks behind refuse it)
}

TEST(ReplayGuardTest, PublisherIdsAreRandomAndNeverZero) {
  std::set<uint64_t> ids;
  for (int i = 0; i < 100; ++i) {
    const uint64_t id = RandomPublisherId();
    EXPECT_NE(id, 0u);
    ids.insert(id);
  }
  EXPECT_EQ(ids.size(), 100u);
}

}  // namespace
}  // namespace birotor
