// Rotor faults and the thrust deficit shared by both rotors, judged from the
// filter's thrust scales mu_i and their covariance, with persistence and
// hysteresis (EkfOptions: rotor_fault_*, thrust_deficit_*, fault_n_sigma,
// fault_persistence_s). The last stage of the EKF's strain step; its facts are
// the method's. The birotor's face of MultiArmFaultMonitor at N = 2 (one set
// of rules for every vehicle). No allocation, no throw, no log.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "estimator/estimator_config.h"
#include "estimator/force_status.h"
#include "estimator/multi_arm_fault_monitor.h"
#include "samples/rotor_count.h"

namespace birotor {

class RotorFaultMonitor {
 public:
  explicit RotorFaultMonitor(const EkfOptions& options);
  void Reset();
  // thrust_scale = (mu1, mu2) [1] at utime [us], covariance their 2x2 block of P.
  // Rotor i weaker than rotor j: d = mu_j - mu_i with var d = P_jj + P_ii - 2 P_ij,
  // flagged when d - n std(d) > rotor_fault_asymmetry held for
  // fault_persistence_s, cleared when d + n std(d) < rotor_fault_clear_asymmetry.
  // Deficit: even the stronger rotor has mu + n std(mu) < thrust_deficit_scale
  // (held as long), cleared when its mu - n std(mu) > thrust_deficit_clear_scale.
  void Update(int64_t utime, const Eigen::Vector2d& thrust_scale, const Eigen::Matrix2d& covariance);
  // The rotor faults and the thrust deficit as flagged, into the method's
  // filter facts (force_status.h composes STATUS_ROTOR*_FAULT and
  // STATUS_THRUST_DEFICIT from them).
  void FillFacts(FilterStatusFacts* facts) const;
  // A rotor fault is flagged on either rotor.
  bool AnyRotorFault() const { return monitor_.fault(0) || monitor_.fault(1); }

 private:
  MultiArmFaultMonitor monitor_;
};

}  // namespace birotor
