#include "estimator/rotor_fault_monitor.h"

#include <algorithm>
#include <cmath>

#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

RotorFaultMonitor::RotorFaultMonitor(const EkfOptions& options)
    : options_(options), persistence_us_(static_cast<int64_t>(options.fault_persistence_s * 1e6)) {}

void RotorFaultMonitor::Reset() { fault_[0] = fault_[1] = deficit_ = Flag(); }

void RotorFaultMonitor::Update(int64_t utime, const Eigen::Vector2d& thrust_scale, const Eigen::Matrix2d& covariance) {
  const double n = options_.fault_n_sigma;
  const double std_d = std::sqrt(std::max(covariance(0, 0) + covariance(1, 1) - 2.0 * covariance(0, 1), 0.0));
  for (int i = 0; i < kBirotorRotors; ++i) {
    const double d = thrust_scale(1 - i) - thrust_scale(i);
    fault_[i].Update(d - n * std_d > options_.rotor_fault_asymmetry,
                     d + n * std_d < options_.rotor_fault_clear_asymmetry, utime, persistence_us_);
  }
  double upper = -1e9, lower = -1e9;  // max over rotors of mu + n std, mu - n std
  for (int i = 0; i < kBirotorRotors; ++i) {
    const double std_mu = std::sqrt(covariance(i, i));
    upper = std::max(upper, thrust_scale(i) + n * std_mu);
    lower = std::max(lower, thrust_scale(i) - n * std_mu);
  }
  deficit_.Update(upper<options_.thrust_deficit_scale, lower> options_.thrust_deficit_clear_scale, utime,
                  persistence_us_);
}

void RotorFaultMonitor::FillFacts(FilterStatusFacts* facts) const {
  facts->rotor_fault[0] = fault_[0].on;
  facts->rotor_fault[1] = fault_[1].on;
  facts->thrust_deficit = deficit_.on;
}

}  // namespace birotor
