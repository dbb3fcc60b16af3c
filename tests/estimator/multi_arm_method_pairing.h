// Test helper: the N-arm simulator on the birotor description feeding an
// N-arm method and the birotor's method of the same name on the same samples
// (the N = 2 samples converted to the birotor's), recording the largest
// difference of their estimates after both have started.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>

#include "estimator/force_estimator.h"
#include "estimator/multi_arm_ekf.h"
#include "samples/sample_sink.h"

namespace birotor {

struct PairDifference {
  int64_t compared = 0;
  double force_n = 0;       // max |f_N - f_birotor| [N]
  double force_std_n = 0;   // max |sigma_N - sigma_birotor| [N]
  double thrust_scale = 0;  // max |mu_N - mu_birotor| [1]
  double largest_force_n = 0;
};

class MethodPairSink : public SampleSink {
 public:
  MethodPairSink(MultiArmForceEstimator* multi, ForceEstimator* birotor) : multi_(multi), birotor_(birotor) {}
  void OnStrainN(const MultiArmStrainSample& sample) override {
    StrainSample s;
    s.utime = sample.utime;
    s.seq = sample.seq;
    s.deflection_rad[0] = sample.deflection_rad[0];
    s.deflection_rad[1] = sample.deflection_rad[1];
    MultiArmForceEstimate multi;
    ForceEstimate birotor;
    StrainStepInfo info;
    multi_->AddStrain(sample, &multi);
    birotor_->AddStrain(s, &birotor, &info, nullptr);
    for (size_t i = 0; i < 2; ++i) {
      diff_.force_n = std::max(diff_.force_n, std::abs(multi.force_n[i] - birotor.force_n[i]));
      diff_.force_std_n = std::max(diff_.force_std_n, std::abs(multi.force_std_n[i] - birotor.force_std_n[i]));
      diff_.thrust_scale = std::max(diff_.thrust_scale, std::abs(multi.thrust_scale[i] - birotor.thrust_scale[i]));
      diff_.largest_force_n = std::max(diff_.largest_force_n, std::abs(birotor.force_n[i]));
    }
    ++diff_.compared;
  }
  void OnMotorN(const MultiArmMotorSample& sample) override {
    MotorSample m;
    m.utime = sample.utime;
    m.seq = sample.seq;
    for (size_t i = 0; i < 2; ++i) {
      m.omega_cmd_rad_s[i] = sample.omega_cmd_rad_s[i];
      m.omega_meas_rad_s[i] = sample.omega_meas_rad_s[i];
    }
    multi_->AddMotor(sample);
    birotor_->AddMotor(m, nullptr);
  }
  void OnImu(const ImuSample& sample) override {
    multi_->AddImu(sample);
    birotor_->AddImu(sample, nullptr);
  }
  const PairDifference& difference() const { return diff_; }

 private:
  MultiArmForceEstimator* multi_;
  ForceEstimator* birotor_;
  PairDifference diff_;
};

}  // namespace birotor
