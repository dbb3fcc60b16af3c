// Rejection of the rotor-harmonic pickup of the strain gauges (gauges.md:
// v_i = a1 sin(theta_i) + a2 sin(2 theta_i + phase)): per arm, second-order
// notches at 1x and 2x the speed of that arm's own rotor, re-tuned at every
// sample from the tracked rotor speed, before any method sees the deflection.
// No allocation, no throw.
#pragma once

#include "estimator/estimator_config.h"
#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

class HarmonicNotch {
 public:
  explicit HarmonicNotch(const HarmonicNotchOptions& options) : options_(options) {}

  // Forgets the filter memory (the next sample passes unchanged).
  void Reset();
  // Filters both deflections in place. dt_s: time since the previous sample
  // [s]; omega_rad_s: the speed of each rotor [rad/s]. A notch whose
  // frequency is below min_speed_rad_s or above 0.45 of the sample rate, or a
  // dt_s outside (0, max_dt_s], passes the sample and restarts from it.
  //   H(z) = g (1 - 2 cos(w0) z^-1 + z^-2) / (1 - 2 r cos(w0) z^-1 + r^2 z^-2),
  //   w0 = h omega dt, r = exp(-pi bandwidth dt), g: unit gain at DC.
  void Apply(double dt_s, const double omega_rad_s[kBirotorRotors], StrainSample* sample);

 private:
  // Direct form I memory of one notch (robust to coefficients that change per sample).
  struct Section {
    double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
    bool primed = false;
  };
  static constexpr int kHarmonics = 2;
  HarmonicNotchOptions options_;
  Section sections_[2][kHarmonics];
};

}  // namespace birotor
