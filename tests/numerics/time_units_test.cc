// utime <-> seconds (numerics/time_units.h).
#include "numerics/time_units.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

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

TEST(TimeUnitsTest, ElapsedSecondsIsDefinedForAnyTwoStamps) {
  EXPECT_EQ(ElapsedSeconds(1500000, 500000), 1.0);
  EXPECT_EQ(ElapsedSeconds(500000, 1500000), -1.0);
  // The extremes a hostile packet can carry: huge, finite, no overflow.
  const int64_t lowest = std::numeric_limits<int64_t>::min();
  const int64_t highest = std::numeric_limits<int64_t>::max();
  EXPECT_NEAR(ElapsedSeconds(highest, lowest), 1.8446744073709552e13, 0.01);  // 2^64 us
  EXPECT_NEAR(ElapsedSeconds(lowest, 1000000), -9.223372036855776e12, 0.01);  // -2^63 us - 1 s
  // Exact to the microsecond below kLatestPlausibleUtime.
  EXPECT_EQ(ElapsedSeconds(kLatestPlausibleUtime, kLatestPlausibleUtime - 1), 1e-6);
}

TEST(TimeUnitsTest, WholeMicroseconds) {
  EXPECT_TRUE(IsWholeMicroseconds(0.001));
  EXPECT_TRUE(IsWholeMicroseconds(1e-6));
  EXPECT_FALSE(IsWholeMicroseconds(1.5e-6));
  EXPECT_FALSE(IsWholeMicroseconds(1e-7));
}

}  // namespace
}  // namespace birotor
