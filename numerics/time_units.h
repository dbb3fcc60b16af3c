// The one conversion between LCM's utime (integer microseconds since the
// Unix epoch, or since the start of a log) and seconds, so that no file
// writes a bare 1e6 or 1e-6 for it.
#pragma once

#include <cmath>
#include <cstdint>

namespace birotor {

constexpr double kUtimePerSecond = 1e6;  // [us/s]

// The latest stamp any clock of ours can plausibly carry: 2^53 us after the
// epoch (year 2255). A clock latched beyond it could overflow int64_t as
// it runs; doubles stop being exact to the microsecond there too.
constexpr int64_t kLatestPlausibleUtime = int64_t{1} << 53;  // [us]

// utime [us] -> seconds [s] (exact for |utime| < 2^53 us, 285 years).
constexpr double UtimeToSeconds(int64_t utime) { return static_cast<double>(utime) / kUtimePerSecond; }

// later_us - earlier_us in seconds [s], for any two stamps: computed in
// double, so a wild stamp from the network (INT64_MIN, INT64_MAX) gives a
// huge but defined figure instead of a signed overflow. Exact to the
// microsecond while both stamps are below 2^53 us.
constexpr double ElapsedSeconds(int64_t later_us, int64_t earlier_us) {
  return (static_cast<double>(later_us) - static_cast<double>(earlier_us)) / kUtimePerSecond;
}

// seconds [s] -> utime [us], rounded to the nearest microsecond.
inline int64_t SecondsToUtime(double seconds) { return std::llround(seconds * kUtimePerSecond); }

// True when seconds is a whole number of microseconds (within 1e-6 us).
inline bool IsWholeMicroseconds(double seconds) {
  return std::fabs(seconds * kUtimePerSecond - std::round(seconds * kUtimePerSecond)) <= 1e-6;
}

}  // namespace birotor
