#include "estimator/harmonic_notch.h"

#include <algorithm>
#include <cmath>

namespace birotor {

HarmonicNotch::HarmonicNotch(const HarmonicNotchOptions& options, int arm_count)
    : options_(options), arm_count_(std::min(std::max(arm_count, kBirotorRotors), kMaxArms)) {}

void HarmonicNotch::Reset() {
  for (auto& arm : sections_) arm.fill(Section());
}

void HarmonicNotch::Apply(double dt_s, const double* omega_rad_s, double* deflection_rad) {
  if (!options_.enabled) return;
  const bool dt_ok = dt_s > 0 && dt_s <= options_.max_dt_s;
  const double r = std::exp(-M_PI * options_.bandwidth_hz * dt_s);
  for (int arm = 0; arm < arm_count_; ++arm) {
    Section* sections = sections_[static_cast<size_t>(arm)].data();
    if (std::isnan(deflection_rad[arm])) {  // no reading: passes, the notches restart at the next one
      for (int h = 0; h < kHarmonics; ++h) sections[h].primed = false;
      continue;
    }
    deflection_rad[arm] = FilterArm(deflection_rad[arm], dt_s, dt_ok, r, omega_rad_s[arm], sections);
  }
}

double HarmonicNotch::FilterArm(double x, double dt_s, bool dt_ok, double r, double omega_rad_s,
                                Section* sections) const {
  for (int h = 0; h < kHarmonics; ++h) {
    Section& s = sections[h];
    const double w0 = (h + 1) * omega_rad_s * dt_s;  // [rad/sample]
    const bool active = dt_ok && s.primed && omega_rad_s >= options_.min_speed_rad_s && w0 <= 0.9 * M_PI;
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
  return x;
}

}  // namespace birotor
