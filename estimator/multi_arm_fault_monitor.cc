#include "estimator/multi_arm_fault_monitor.h"

#include <algorithm>
#include <cmath>

namespace birotor {

MultiArmFaultMonitor::MultiArmFaultMonitor(const EkfOptions& options)
    : options_(options),
      persistence_us_(static_cast<int64_t>(options.fault_persistence_s * 1e6)),
      second_rotor_persistence_us_(static_cast<int64_t>(options.fault_second_rotor_persistence_s * 1e6)),
      second_rotor_window_us_(static_cast<int64_t>(options.fault_second_rotor_window_s * 1e6)) {}

void MultiArmFaultMonitor::Reset() {
  fault_.fill(Flag());
  deficit_ = Flag();
  last_raised_rotor_ = -1;
}

int64_t MultiArmFaultMonitor::PersistenceUs(int rotor, int64_t utime) const {
  const bool after_another = last_raised_rotor_ >= 0 && last_raised_rotor_ != rotor && utime >= last_raised_utime_ &&
                             utime - last_raised_utime_ < second_rotor_window_us_;
  return after_another ? std::max(persistence_us_, second_rotor_persistence_us_) : persistence_us_;
}

void MultiArmFaultMonitor::Update(int64_t utime, int n, const ScaleVector& thrust_scale,
                                  const ScaleMatrix& covariance) {
  const double n_sigma = options_.fault_n_sigma;
  const double other_weight = 1.0 / (n - 1);
  for (int i = 0; i < n; ++i) {
    double d = -thrust_scale(i), var_d = 0.0;
    for (int j = 0; j < n; ++j) {
      const double a_j = j == i ? -1.0 : other_weight;
      if (j != i) d += other_weight * thrust_scale(j);
      for (int k = 0; k < n; ++k) var_d += a_j * covariance(j, k) * (k == i ? -1.0 : other_weight);
    }
    const double std_d = std::sqrt(std::max(var_d, 0.0));
    Flag& flag = fault_[static_cast<size_t>(i)];
    const bool was_on = flag.on;
    flag.Update(d - n_sigma * std_d > options_.rotor_fault_asymmetry,
                d + n_sigma * std_d < options_.rotor_fault_clear_asymmetry, utime, PersistenceUs(i, utime));
    if (flag.on && !was_on) {
      last_raised_rotor_ = i;
      last_raised_utime_ = utime;
    }
  }
  double upper = -1e9, lower = -1e9;  // max over rotors of mu + n std, mu - n std
  for (int i = 0; i < n; ++i) {
    const double std_mu = std::sqrt(std::max(covariance(i, i), 0.0));
    upper = std::max(upper, thrust_scale(i) + n_sigma * std_mu);
    lower = std::max(lower, thrust_scale(i) - n_sigma * std_mu);
  }
  deficit_.Update(upper<options_.thrust_deficit_scale, lower> options_.thrust_deficit_clear_scale, utime,
                  persistence_us_);
}

void MultiArmFaultMonitor::FillFacts(int n, MultiArmFilterFacts* facts) const {
  for (int i = 0; i < n; ++i) facts->rotor_fault[static_cast<size_t>(i)] = fault_[static_cast<size_t>(i)].on;
  facts->thrust_deficit = deficit_.on;
}

}  // namespace birotor
