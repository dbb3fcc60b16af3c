// The sample schedule on the fixed integration step, shared by the birotor
// and the N-arm simulators (times in whole microseconds: numerics/time_units.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "numerics/time_units.h"

namespace birotor {

// Integration steps between two samples of a sensor at rate_hz (at least 1).
inline int64_t StepsPerSample(double rate_hz, double step_s) {
  return std::max<int64_t>(1, std::llround(1.0 / (rate_hz * step_s)));
}

// First multiple of period_us at or after t_us, as a sample index.
inline int64_t FirstSampleAtOrAfter(int64_t t_us, int64_t period_us) { return (t_us + period_us - 1) / period_us; }

}  // namespace birotor
