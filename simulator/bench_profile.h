// Open-loop rotor speed commands for the test-stand scenario: segments that
// alternate between random steps (independent per rotor) and a linear chirp,
// all between omega_low and omega_high.
#pragma once

#include <cstdint>

#include "simulator/flight_controller.h"
#include "simulator/noise.h"
#include "simulator/scenario.h"

namespace birotor {

class BenchCommander {
 public:
  BenchCommander(const BenchProfile& profile, uint64_t seed);

  // Command at t_s; call with non-decreasing times.
  RotorCommand At(double t_s);

 private:
  BenchProfile profile_;
  GaussianSource source_;
  int64_t step_index_ = -1;  // index of the current random step
  double step_level_rad_s_[2] = {0.0, 0.0};
};

}  // namespace birotor
