// The airborne test on an estimator's reports: the rotors' summed force
// above airborne_force_fraction of the weight for airborne_s (stamps of the
// reports). Once airborne, airborne for good. Plain data, no allocation.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "controller/controller_params.h"
#include "controller/rotor_efficiency_estimate.h"
#include "numerics/time_units.h"

namespace birotor {

class AirborneByForce {
 public:
  // weight_n: the thrust the rotors make together in hover [N].
  AirborneByForce(const EfficiencyParams& params, double weight_n, int rotor_count)
      : fraction_(params.airborne_force_fraction),
        hold_s_(params.airborne_s),
        weight_n_(weight_n),
        rotor_count_(rotor_count) {}

  // One report; true once airborne (the report that makes it airborne
  // returns false: it is not followed yet).
  bool Note(const RotorEfficiencyEstimate& e) {
    if (airborne_) return true;
    double total_n = 0.0;  // sum_i f_i [N]
    for (int i = 0; i < rotor_count_; ++i) total_n += e.force_n[static_cast<size_t>(i)];
    if (total_n < fraction_ * weight_n_) {
      above_since_us_ = -1;
      return false;
    }
    if (above_since_us_ < 0) above_since_us_ = e.utime;
    airborne_ = ElapsedSeconds(e.utime, above_since_us_) >= hold_s_;
    return false;
  }
  bool airborne() const { return airborne_; }

 private:
  double fraction_;
  double hold_s_;
  double weight_n_;
  int rotor_count_;
  bool airborne_ = false;
  int64_t above_since_us_ = -1;
};

// A report's force sigma small enough to follow: force_std_i at most
// max_relative_sigma x the larger of |force_i| and the rotors' mean hover
// thrust (a dead rotor's 0 N is certain, not infinitely uncertain relative
// to itself).
inline bool PreciseEnough(double force_n, double force_std_n, double mean_hover_n, double max_relative_sigma) {
  return force_std_n <= max_relative_sigma * std::max(std::fabs(force_n), mean_hover_n);
}

}  // namespace birotor
