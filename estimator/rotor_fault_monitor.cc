#include "estimator/rotor_fault_monitor.h"

#include "samples/rotor_count.h"

namespace birotor {

RotorFaultMonitor::RotorFaultMonitor(const EkfOptions& options) : monitor_(options) {}

void RotorFaultMonitor::Reset() { monitor_.Reset(); }

void RotorFaultMonitor::Update(int64_t utime, const Eigen::Vector2d& thrust_scale, const Eigen::Matrix2d& covariance) {
  // Update reads only the leading kBirotorRotors entries: the rest is left unset.
  MultiArmFaultMonitor::ScaleVector scales;
  MultiArmFaultMonitor::ScaleMatrix scale_covariance;
  scales.head<kBirotorRotors>() = thrust_scale;
  scale_covariance.topLeftCorner<kBirotorRotors, kBirotorRotors>() = covariance;
  monitor_.Update(utime, kBirotorRotors, scales, scale_covariance);
}

void RotorFaultMonitor::FillFacts(FilterStatusFacts* facts) const {
  for (int i = 0; i < kBirotorRotors; ++i) facts->rotor_fault[i] = monitor_.fault(i);
  facts->thrust_deficit = monitor_.thrust_deficit();
}

}  // namespace birotor
