// The host's clocks, for the programs and their LCM glue (the libraries run on
// sample stamps, never on these): the wall clock for stamps and receive
// times, the monotonic clock for periods, rates, timeouts and elapsed times.
#pragma once

#include <chrono>
#include <cstdint>

namespace birotor {

// Wall clock [us since the Unix epoch]; jumps when the host's time is set.
inline int64_t WallClockUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// Monotonic clock [us], arbitrary origin.
inline int64_t SteadyClockUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Monotonic clock [ns], arbitrary origin.
inline int64_t SteadyClockNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Monotonic clock [s], arbitrary origin.
inline double SteadyClockS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Monotonic time elapsed since construction [s].
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double ElapsedS() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace birotor
