#include "estimator/harmonic_notch.h"

#include <cmath>

#include "samples/rotor_count.h"

namespace birotor {

void HarmonicNotch::Reset() {
  for (auto& arm : sections_) {
    for (Section& s : arm) s = Section();
  }
}

void HarmonicNotch::Apply(double dt_s, const double omega_rad_s[kBirotorRotors], StrainSample* sample) {
  if (!options_.enabled) return;
  const bool dt_ok = dt_s > 0 && dt_s <= options_.max_dt_s;
  const double r = std::exp(-M_PI * options_.bandwidth_hz * dt_s);
  for (int arm = 0; arm < kBirotorRotors; ++arm) {
    double x = sample->deflection_rad[arm];
    for (int h = 0; h < kHarmonics; ++h) {
      Section& s = sections_[arm][h];
      const double w0 = (h + 1) * omega_rad_s[arm] * dt_s;  // [rad/sample]
      const bool active = dt_ok && s.primed && omega_rad_s[arm] >= options_.min_speed_rad_s && w0 <= 0.9 * M_PI;
      double y = x;
      if (active) {
        const double c = std::cos(w0);
        const double gain = (1.0 - 2.0 * r * c + r * r) / (2.0 - 2.0 * c);
        y = gain * (x - 2.0 * c * s.x1 + s.x2) + 2.0 * r * c * s.y1 - r * r * s.y2;
        s.x2 = s.x1;
        s.y2 = s.y1;
        s.x1 = x;
        s.y1 = y;
      } else {
        // Pass through; the memory restarts at this value (steady state of a constant input).
        s.x1 = s.x2 = s.y1 = s.y2 = x;
        s.primed = true;
      }
      x = y;
    }
    sample->deflection_rad[arm] = x;
  }
}

}  // namespace birotor
