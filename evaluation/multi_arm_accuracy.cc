#include "evaluation/multi_arm_accuracy.h"

#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "estimator/multi_arm_ekf.h"
#include "samples/sample_sink.h"
#include "simulator/multi_arm_simulator.h"

namespace birotor {
namespace {

// Feeds the filter and scores each estimate against the truth of its utime
// (the simulator emits STRAIN_N before TRUTH_N in the same step).
class AccuracySink : public SampleSink {
 public:
  AccuracySink(MultiArmForceEstimator* filter, int n, const EvalOptions& options)
      : filter_(filter), n_(n), options_(options) {
    result_.n_rotors = n;
    result_.detection_delay_s = std::numeric_limits<double>::quiet_NaN();
  }
  void OnStrainN(const MultiArmStrainSample& sample) override {
    filter_->AddStrain(sample, &pending_);
    has_pending_ = true;
    if (first_estimate_utime_ < 0) first_estimate_utime_ = sample.utime;
  }
  void OnMotorN(const MultiArmMotorSample& sample) override { filter_->AddMotor(sample); }
  void OnImu(const ImuSample& sample) override { filter_->AddImu(sample); }
  void OnTruthN(const MultiArmTruthSample& truth) override {
    if (first_truth_utime_ < 0) first_truth_utime_ = truth.utime;
    DetectStep(truth);
    if (has_pending_ && pending_.utime == truth.utime) Score(pending_, truth);
    has_pending_ = false;
  }
  MultiArmAccuracy Finish() {
    int64_t valid = 0;
    for (int i = 0; i < n_; ++i) {
      MultiArmRotorAccuracy& r = result_.rotor[static_cast<size_t>(i)];
      if (r.count > 0) {
        r.mae_n = abs_sum_[static_cast<size_t>(i)] / static_cast<double>(r.count);
        r.share_within_2sigma = static_cast<double>(within_[static_cast<size_t>(i)]) / static_cast<double>(r.count);
      }
    }
    valid = valid_count_;
    if (result_.scored > 0) result_.valid_share = static_cast<double>(valid) / static_cast<double>(result_.scored);
    return result_;
  }

 private:
  void DetectStep(const MultiArmTruthSample& truth) {
    if (has_last_truth_ && result_.step_rotor == 0) {
      for (int i = 0; i < n_; ++i) {
        const size_t k = static_cast<size_t>(i);
        if (std::abs(truth.thrust_scale[k] - last_truth_scale_[k]) > options_.step_threshold) {
          result_.step_rotor = i + 1;
          step_utime_ = truth.utime;
          result_.step_time_s = static_cast<double>(truth.utime - first_truth_utime_) * 1e-6;
          break;
        }
      }
    }
    last_truth_scale_ = truth.thrust_scale;
    has_last_truth_ = true;
  }
  void Score(const MultiArmForceEstimate& e, const MultiArmTruthSample& truth) {
    if (result_.step_rotor > 0 && std::isnan(result_.detection_delay_s) &&
        (e.rotor_fault_bits >> (result_.step_rotor - 1) & 1) != 0) {
      result_.detection_delay_s = static_cast<double>(e.utime - step_utime_) * 1e-6;
    }
    for (int i = 0; i < n_; ++i) {
      const bool flagged = (e.rotor_fault_bits >> i & 1) != 0;
      if (flagged && truth.thrust_scale[static_cast<size_t>(i)] > options_.false_alarm_truth_scale) {
        ++result_.false_alarms;
      }
    }
    if (static_cast<double>(e.utime - first_estimate_utime_) * 1e-6 < options_.warmup_s) return;
    bool finite = true;
    for (int i = 0; i < n_; ++i) {
      const size_t k = static_cast<size_t>(i);
      finite = finite && std::isfinite(e.force_n[k]) && std::isfinite(e.force_std_n[k]);
    }
    if (!finite) {
      ++result_.nonfinite;
      return;
    }
    ++result_.scored;
    valid_count_ += (e.status & kStatusValid) != 0;
    for (int i = 0; i < n_; ++i) {
      const size_t k = static_cast<size_t>(i);
      const double error = std::abs(e.force_n[k] - truth.force_n[k]);
      ++result_.rotor[k].count;
      abs_sum_[k] += error;
      within_[k] += error <= 2.0 * e.force_std_n[k];
    }
  }

  MultiArmForceEstimator* filter_;
  int n_;
  EvalOptions options_;
  MultiArmAccuracy result_;
  MultiArmForceEstimate pending_;
  bool has_pending_ = false;
  int64_t first_estimate_utime_ = -1, first_truth_utime_ = -1, step_utime_ = 0, valid_count_ = 0;
  ArmValues last_truth_scale_{};
  bool has_last_truth_ = false;
  std::array<double, kMaxArms> abs_sum_{};
  std::array<int64_t, kMaxArms> within_{};
};

}  // namespace

MultiArmAccuracy RunMultiArmAccuracy(const VehicleDescription& vehicle, const Scenario& scenario, const EkfOptions& ekf,
                                     const EvalOptions& options) {
  const std::unique_ptr<MultiArmForceEstimator> filter = MakeMultiArmEkf(vehicle, ekf);
  if (filter == nullptr) throw std::invalid_argument("no N-arm EKF for arm_count " + std::to_string(vehicle.arm_count));
  MultiArmSimulator simulator(vehicle, scenario);
  AccuracySink sink(filter.get(), vehicle.arm_count, options);
  simulator.Run(&sink);
  return sink.Finish();
}

std::string MultiArmAccuracyHeader() {
  return "| scenario | MAE per rotor [N] | 2-sigma share per rotor | VALID share | step rotor | detection [ms] | "
         "false alarms |\n|---|---|---|---|---|---|---|\n";
}

std::string MultiArmAccuracyRow(const std::string& scenario, const MultiArmAccuracy& result) {
  std::ostringstream row;
  row.setf(std::ios::fixed);
  const auto joined = [&](auto value, int precision) {
    std::ostringstream out;
    out.setf(std::ios::fixed);
    out.precision(precision);
    for (int i = 0; i < result.n_rotors; ++i)
      out << (i > 0 ? " / " : "") << value(result.rotor[static_cast<size_t>(i)]);
    return out.str();
  };
  row.precision(3);
  row << "| " << scenario << " | " << joined([](const MultiArmRotorAccuracy& r) { return r.mae_n; }, 4) << " | "
      << joined([](const MultiArmRotorAccuracy& r) { return r.share_within_2sigma; }, 3) << " | " << result.valid_share
      << " | ";
  if (result.step_rotor > 0) {
    row.precision(1);
    row << result.step_rotor << " | " << result.detection_delay_s * 1e3 << " | ";
  } else {
    row << "- | - | ";
  }
  row << result.false_alarms << " |\n";
  return row.str();
}

}  // namespace birotor
