// utime <-> seconds (numerics/time_units.h).
#include "numerics/time_units.h"

#include <gtest/gtest.h>

namespace birotor {
namespace {

TEST(TimeUnitsTest, UtimeIsMicroseconds) {
  EXPECT_EQ(UtimeToSeconds(1500000), 1.5);
  EXPECT_EQ(UtimeToSeconds(-250), -0.00025);
  EXPECT_EQ(SecondsToUtime(1.5), 1500000);
  EXPECT_EQ(SecondsToUtime(0.0000004), 0);  // 0.4 us rounds to 0
  EXPECT_EQ(SecondsToUtime(0.0000006), 1);  // 0.6 us rounds to 1
  // A day of utime since the epoch of 2026 survives the round trip exactly.
  const int64_t utime = 1796083200000000 + 86399999999;
  EXPECT_EQ(SecondsToUtime(UtimeToSeconds(utime)), utime);
}

TEST(TimeUnitsTest, WholeMicroseconds) {
  EXPECT_TRUE(IsWholeMicroseconds(0.001));
  EXPECT_TRUE(IsWholeMicroseconds(1e-6));
  EXPECT_FALSE(IsWholeMicroseconds(1.5e-6));
  EXPECT_FALSE(IsWholeMicroseconds(1e-7));
}

}  // namespace
}  // namespace birotor
