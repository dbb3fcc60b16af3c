// Open-loop rotor speed commands for the test-stand scenario: segments that
// alternate between random steps (independent per rotor) and a linear chirp,
// all between omega_low and omega_high, for any number of rotors.
#pragma once

#include <array>
#include <cstdint>

#include "model/vehicle_description.h"
#include "simulator/flight_controller.h"
#include "simulator/noise.h"
#include "simulator/scenario.h"

namespace birotor {

class BenchCommander {
 public:
  // rotor_count: 1 .. kMaxArms rotors (the birotor: 2).
  BenchCommander(const BenchProfile& profile, uint64_t seed, int rotor_count = kBirotorArmCount);

  // Speeds of rotors [0, rotor_count) at t_s [rad/s]; call with
  // non-decreasing times. Random steps: a new level per rotor, uniform in
  // [low, high], every step_hold_s (drawn rotor by rotor); chirp: phase
  // 2 pi (f0 t + (f1 - f0) t^2 / (2 T)), odd rotors in phase, even rotors
  // (2, 4, ..) in antiphase.
  const std::array<double, kMaxArms>& Speeds(double t_s);
  // The birotor's two rotors as a RotorCommand.
  RotorCommand At(double t_s);

 private:
  BenchProfile profile_;
  GaussianSource source_;
  int rotor_count_;
  int64_t step_index_ = -1;  // index of the current random step
  std::array<double, kMaxArms> step_level_rad_s_{};
  std::array<double, kMaxArms> speeds_rad_s_{};
};

}  // namespace birotor
