// The one conversion between LCM's utime (integer microseconds since the
// Unix epoch, or since the start of a log) and seconds, so that no file
// writes a bare 1e6 or 1e-6 for it.
#pragma once

#include <cmath>
#include <cstdint>

namespace birotor {

constexpr double kUtimePerSecond = 1e6;  // [us/s]

// utime [us] -> seconds [s] (exact for |utime| < 2^53 us, 285 years).
constexpr double UtimeToSeconds(int64_t utime) { return static_cast<double>(utime) / kUtimePerSecond; }

// seconds [s] -> utime [us], rounded to the nearest microsecond.
inline int64_t SecondsToUtime(double seconds) { return std::llround(seconds * kUtimePerSecond); }

// True when seconds is a whole number of microseconds (within 1e-6 us).
inline bool IsWholeMicroseconds(double seconds) {
  return std::fabs(seconds * kUtimePerSecond - std::round(seconds * kUtimePerSecond)) <= 1e-6;
}

}  // namespace birotor
