// Test helper: the N-arm simulator on the birotor description feeding an
// N-arm method and the birotor's method of the same name on the same samples
// (the N = 2 samples converted to the birotor's), recording the largest
// difference of their estimates after both have started, and of their
// fusion reports over each strain step (the N-arm method's reports() against
// what the birotor's appended over the same calls).
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
  int64_t reports_compared = 0;
  int64_t report_steps_differing = 0;  // steps whose count, sources or outcomes differ
  double nis = 0;                      // max |NIS_N - NIS_birotor| (both finite; a NaN against a number counts above)
  double innovation = 0;               // max |y_N - y_birotor| over the components, in the measurement's unit
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
    birotor_->AddStrain(s, &birotor, &info, &birotor_reports_);
    CompareReports();
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
    birotor_->AddMotor(m, &birotor_reports_);
  }
  void OnImu(const ImuSample& sample) override {
    multi_->AddImu(sample);
    birotor_->AddImu(sample, &birotor_reports_);
  }
  const PairDifference& difference() const { return diff_; }

 private:
  void CompareReports() {
    const FusionReports* multi = multi_->reports();
    bool differs = multi == nullptr || multi->size() != birotor_reports_.size();
    for (int k = 0; !differs && k < multi->size(); ++k) {
      const FusionReport& a = (*multi)[k];
      const FusionReport& b = birotor_reports_[k];
      differs = a.source != b.source || a.outcome != b.outcome || a.size != b.size;
      if (std::isfinite(a.nis) != std::isfinite(b.nis)) {
        diff_.nis = std::max(diff_.nis, 1.0);
      } else if (std::isfinite(a.nis)) {
        diff_.nis = std::max(diff_.nis, std::abs(a.nis - b.nis));
      }
      for (int j = 0; !differs && j < a.size; ++j) {
        diff_.innovation = std::max(diff_.innovation, std::abs(a.innovation(j) - b.innovation(j)));
      }
      ++diff_.reports_compared;
    }
    if (differs) ++diff_.report_steps_differing;
    birotor_reports_.clear();
  }

  MultiArmForceEstimator* multi_;
  ForceEstimator* birotor_;
  FusionReports birotor_reports_;  // the birotor method's since the previous strain step
  PairDifference diff_;
};

}  // namespace birotor
