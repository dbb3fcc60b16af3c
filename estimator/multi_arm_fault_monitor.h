// Rotor faults and the thrust deficit of a vehicle with N rotors, judged from
// the filter's thrust scales mu_i and their covariance with the birotor's
// rules and keys (RotorFaultMonitor, EkfOptions rotor_fault_*,
// thrust_deficit_*, fault_n_sigma, fault_persistence_s): rotor i is compared
// with the mean of the others, which for N = 2 is the other rotor (the
// birotor's test, tests/estimator/multi_arm_ekf_test.cc). No allocation,
// no throw, no log.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "estimator/estimator_config.h"
#include "estimator/force_status.h"
#include "estimator/persistent_flag.h"
#include "model/vehicle_description.h"

namespace birotor {

class MultiArmFaultMonitor {
 public:
  using ScaleVector = Eigen::Matrix<double, kMaxArms, 1>;
  using ScaleMatrix = Eigen::Matrix<double, kMaxArms, kMaxArms>;

  explicit MultiArmFaultMonitor(const EkfOptions& options);
  void Reset();
  // thrust_scale: mu_0 .. mu_(n-1) [1] at utime [us]; covariance: their
  // block of P (top-left n x n used). With a = the mean-of-the-others weights
  // (a_j = 1 / (n - 1) for j != i, a_i = -1):
  //   d_i = a^T mu,  var d_i = a^T P_mu a;
  // flagged when d_i - n_sigma std(d_i) > rotor_fault_asymmetry held for
  // fault_persistence_s, cleared when d_i + n_sigma std(d_i) < rotor_fault_clear_asymmetry.
  // Within fault_second_rotor_window_s of another rotor's raise it must hold
  // fault_second_rotor_persistence_s instead: the first loss's transient
  // swings the other thrust scales for a few milliseconds (EkfOptions).
  // Deficit: even the strongest rotor has mu + n_sigma std(mu) < thrust_deficit_scale.
  void Update(int64_t utime, int n, const ScaleVector& thrust_scale, const ScaleMatrix& covariance);
  void FillFacts(int n, MultiArmFilterFacts* facts) const;
  bool fault(int rotor) const { return fault_[static_cast<size_t>(rotor)].on; }
  bool thrust_deficit() const { return deficit_.on; }

 private:
  using Flag = PersistentFlag;

  // The persistence rotor i's flag needs at utime [us].
  int64_t PersistenceUs(int rotor, int64_t utime) const;

  EkfOptions options_;
  int64_t persistence_us_;
  int64_t second_rotor_persistence_us_;
  int64_t second_rotor_window_us_;
  std::array<Flag, kMaxArms> fault_{};
  Flag deficit_;
  int last_raised_rotor_ = -1;     // the rotor whose flag went on last; -1 none since Reset
  int64_t last_raised_utime_ = 0;  // when [us]
};

}  // namespace birotor
