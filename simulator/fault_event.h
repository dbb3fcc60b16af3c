// The injected faults as the simulators report them (one record per affected
// sample or thrust step), shared by the birotor and the N-arm simulator.
#pragma once

#include <cstdint>

#include "numerics/time_units.h"
#include "simulator/scenario.h"

namespace birotor {

enum class FaultKind {
  kThrustStep,         // s_i changed; rotor, value = new s_i
  kStrainGap,          // strain sample seq not emitted
  kStrainSpike,        // strain sample seq carries a spike; rotor, value = spike [rad]
  kStrainNan,          // strain sample seq is NaN on every arm
  kStrainOutOfOrder,   // strain sample seq emitted after seq + 1
  kMotorTelemetryGap,  // motor sample seq has omega_meas NaN
};

// One injected fault, so tests can check it happened exactly where configured.
struct FaultEvent {
  FaultKind kind = FaultKind::kThrustStep;
  int64_t utime = 0;  // time of the affected sample or step [us]
  int32_t seq = -1;   // seq of the affected sample (-1 for thrust steps)
  int rotor = 0;      // 1 .. N where it applies, 0 otherwise
  double value = 0.0;
};

// Whether t_us lies in [start, start + duration) of window, its times
// counted from offset_us [us]; a window of duration 0 holds nothing.
inline bool InTimeWindow(const TimeWindow& window, int64_t t_us, int64_t offset_us) {
  const int64_t start_us = offset_us + SecondsToUtime(window.start_s);
  return window.duration_s > 0.0 && t_us >= start_us && t_us < start_us + SecondsToUtime(window.duration_s);
}

}  // namespace birotor
