// Rejection of the rotor-harmonic pickup of the strain gauges (gauges.md:
// v_i = a1 sin(theta_i) + a2 sin(2 theta_i + phase)): per arm, second-order
// notches at 1x and 2x the speed of that arm's own rotor, re-tuned at every
// sample from the tracked rotor speed, before any method sees the deflection.
// Any arm count 2 .. kMaxArms (the birotor's pipeline: 2, MultiArmPipeline:
// the vehicle's). No allocation, no throw.
#pragma once

#include <array>

#include "estimator/estimator_config.h"
#include "samples/multi_arm_samples.h"
#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

class HarmonicNotch {
 public:
  // arm_count: 2 .. kMaxArms (clamped to that range).
  explicit HarmonicNotch(const HarmonicNotchOptions& options, int arm_count = kBirotorRotors);

  // Forgets the filter memory (the next sample passes unchanged).
  void Reset();
  // Filters the arm_count deflections in place. dt_s: time since the previous
  // sample [s]; omega_rad_s: the speed of each arm's rotor [rad/s]. A notch
  // whose frequency is below min_speed_rad_s or above 0.45 of the sample
  // rate, or a dt_s outside (0, max_dt_s], passes the sample and restarts
  // from it; a NaN deflection (no reading of that arm) passes and the arm's
  // notches restart at its next reading.
  //   H(z) = g (1 - 2 cos(w0) z^-1 + z^-2) / (1 - 2 r cos(w0) z^-1 + r^2 z^-2),
  //   w0 = h omega dt, r = exp(-pi bandwidth dt), g: unit gain at DC.
  void Apply(double dt_s, const double* omega_rad_s, double* deflection_rad);
  // The birotor's strain sample (arm_count 2).
  void Apply(double dt_s, const double omega_rad_s[kBirotorRotors], StrainSample* sample) {
    Apply(dt_s, omega_rad_s, sample->deflection_rad);
  }
  // An N-arm strain sample of this arm count.
  void Apply(double dt_s, const std::array<double, kMaxArms>& omega_rad_s, MultiArmStrainSample* sample) {
    Apply(dt_s, omega_rad_s.data(), sample->deflection_rad.data());
  }

  int arm_count() const { return arm_count_; }

 private:
  // Direct form I memory of one notch (robust to coefficients that change per sample).
  struct Section {
    double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
    bool primed = false;
  };
  static constexpr int kHarmonics = 2;
  // One arm's two notches in series; returns the filtered deflection.
  double FilterArm(double x, double dt_s, bool dt_ok, double r, double omega_rad_s, Section* sections) const;

  HarmonicNotchOptions options_;
  int arm_count_;
  std::array<std::array<Section, kHarmonics>, kMaxArms> sections_{};
};

}  // namespace birotor
