// The sample schedule on the fixed integration step, shared by the birotor
// and the N-arm simulators (times in whole microseconds: numerics/time_units.h).
#pragma once

#include <cstdint>

#include "numerics/time_units.h"

namespace birotor {

// First multiple of period_us at or after t_us, as a sample index.
inline int64_t FirstSampleAtOrAfter(int64_t t_us, int64_t period_us) { return (t_us + period_us - 1) / period_us; }

}  // namespace birotor
