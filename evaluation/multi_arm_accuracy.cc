#include "evaluation/multi_arm_accuracy.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "birotor/force_estimate_n_t.hpp"
#include "birotor/truth_n_t.hpp"
#include "estimator/multi_arm_pipeline.h"
#include "samples/sample_sink.h"
#include "simulator/multi_arm_simulator.h"
#include "transport/channels.h"
#include "transport/counted_messages.h"
#include "transport/lcm_codec.h"
#include "transport/log_io.h"

namespace birotor {
MultiArmAccuracyScorer::MultiArmAccuracyScorer(int n_rotors, const EvalOptions& options)
    : n_(n_rotors), options_(options), score_from_utime_(options.score_from_utime) {
  result_.n_rotors = n_rotors;
  result_.detection_delay_s = std::numeric_limits<double>::quiet_NaN();
}

void MultiArmAccuracyScorer::AddEstimate(const MultiArmForceEstimate& estimate) {
  pending_ = estimate;
  has_pending_ = true;
  if (first_estimate_utime_ < 0) first_estimate_utime_ = estimate.utime;
}

void MultiArmAccuracyScorer::AddTruth(const MultiArmTruthSample& truth) {
  if (first_truth_utime_ < 0) first_truth_utime_ = truth.utime;
  DetectStep(truth);
  if (has_pending_ && pending_.utime == truth.utime) Score(pending_, truth);
  has_pending_ = false;
}

MultiArmAccuracy MultiArmAccuracyScorer::Finish() const {
  MultiArmAccuracy result = result_;
  for (int i = 0; i < n_; ++i) {
    const size_t k = static_cast<size_t>(i);
    MultiArmRotorAccuracy& r = result.rotor[k];
    if (r.count > 0) {
      r.mae_n = abs_sum_[k] / static_cast<double>(r.count);
      r.share_within_2sigma = static_cast<double>(within_[k]) / static_cast<double>(r.count);
    }
  }
  if (result.scored > 0) {
    result.valid_share = static_cast<double>(valid_count_) / static_cast<double>(result.scored);
    result.mismatch_share = static_cast<double>(mismatch_count_) / static_cast<double>(result.scored);
  }
  return result;
}

void MultiArmAccuracyScorer::DetectStep(const MultiArmTruthSample& truth) {
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

void MultiArmAccuracyScorer::Score(const MultiArmForceEstimate& e, const MultiArmTruthSample& truth) {
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
  if (e.utime < score_from_utime_) {
    ++result_.before_liftoff;
    bool beyond = false;
    for (int i = 0; i < n_; ++i) {
      const size_t k = static_cast<size_t>(i);
      beyond = beyond || std::abs(e.force_n[k] - truth.force_n[k]) > 3.0 * e.force_std_n[k];
    }
    result_.before_liftoff_valid_beyond_3sigma += beyond && (e.status & kStatusValid) != 0;
    return;
  }
  ++result_.scored;
  valid_count_ += (e.status & kStatusValid) != 0;
  mismatch_count_ += (e.status & kStatusModelMismatch) != 0;
  for (int i = 0; i < n_; ++i) {
    const size_t k = static_cast<size_t>(i);
    const double error = std::abs(e.force_n[k] - truth.force_n[k]);
    ++result_.rotor[k].count;
    abs_sum_[k] += error;
    within_[k] += error <= 2.0 * e.force_std_n[k];
  }
}

namespace {

// Feeds the estimator's input path (the daemon's, MultiArmPipeline) and
// scores each estimate against the truth of its utime (the simulator emits
// STRAIN_N before TRUTH_N in the same step).
class AccuracySink : public SampleSink {
 public:
  AccuracySink(MultiArmPipeline* pipeline, const MultiArmSimulator* simulator, bool ground_phase, int n,
               const EvalOptions& options)
      : pipeline_(pipeline), simulator_(simulator), ground_phase_(ground_phase), scorer_(n, options) {}
  void OnStrainN(const MultiArmStrainSample& sample) override {
    MultiArmForceEstimate estimate;
    if (pipeline_->OnStrain(sample, &estimate)) scorer_.AddEstimate(estimate);
  }
  void OnMotorN(const MultiArmMotorSample& sample) override { pipeline_->OnMotor(sample); }
  void OnImu(const ImuSample& sample) override { pipeline_->OnImu(sample); }
  void OnPose(const PoseSample& sample) override { pipeline_->OnPose(sample); }
  void OnTruthN(const MultiArmTruthSample& truth) override {
    if (ground_phase_) {  // on the ground until the simulator saw the lift-off
      const int64_t liftoff = simulator_->liftoff_utime();
      scorer_.SetScoreFrom(liftoff >= 0 ? liftoff : std::numeric_limits<int64_t>::max());
    }
    scorer_.AddTruth(truth);
  }
  MultiArmAccuracy Finish() const { return scorer_.Finish(); }

 private:
  MultiArmPipeline* pipeline_;
  const MultiArmSimulator* simulator_;
  bool ground_phase_;
  MultiArmAccuracyScorer scorer_;
};

}  // namespace

MultiArmAccuracy RunMultiArmAccuracy(const VehicleDescription& vehicle, const Scenario& scenario,
                                     const EstimatorConfig& estimator, const EvalOptions& options) {
  EstimatorConfig config = estimator;
  config.vehicle = vehicle;
  return RunMultiArmAccuracyFlying(vehicle, scenario, config, options);
}

MultiArmAccuracy RunMultiArmAccuracyFlying(const VehicleDescription& flown, const Scenario& scenario,
                                           const EstimatorConfig& estimator, const EvalOptions& options) {
  if (flown.arm_count != estimator.vehicle.arm_count) {
    throw std::invalid_argument("the flown vehicle has " + std::to_string(flown.arm_count) +
                                " arms, the estimator's description " + std::to_string(estimator.vehicle.arm_count));
  }
  MultiArmPipeline pipeline(estimator);  // throws for a description it cannot serve
  MultiArmSimulator simulator(flown, scenario);
  AccuracySink sink(&pipeline, &simulator, scenario.ground.enabled, flown.arm_count, options);
  simulator.Run(&sink);
  return sink.Finish();
}

namespace {

// Every decodable FORCE_N and TRUTH_N of the log with n_rotors entries.
bool ReadForcesAndTruth(const std::string& path, const std::string& prefix, int n_rotors,
                        std::vector<MultiArmForceEstimate>* forces, std::vector<MultiArmTruthSample>* truths,
                        std::string* error) {
  const ChannelNames channels = MakeChannelNames(prefix);
  LogReader reader;
  if (!reader.Open(path, error)) return false;
  LogEvent event;
  force_estimate_n_t force;
  truth_n_t truth;
  while (reader.Next(&event)) {
    if (event.channel == channels.force_n &&
        DecodeMessage(event.data.data(), event.data.size(), &force) == DecodeError::kNone &&
        force.n_rotors == n_rotors) {
      forces->emplace_back();
      FromMessage(force, &forces->back());
    } else if (event.channel == channels.truth_n &&
               DecodeMessage(event.data.data(), event.data.size(), &truth) == DecodeError::kNone &&
               truth.n_arms == n_rotors) {
      truths->emplace_back();
      FromMessage(truth, &truths->back());
    }
  }
  return CheckLogUsable(reader, path, kDefaultMinUsableLogFraction, error);
}

}  // namespace

bool ScoreMultiArmLog(const std::string& path, const std::string& prefix, int n_rotors, const EvalOptions& options,
                      MultiArmAccuracy* result, std::string* error) {
  std::vector<MultiArmForceEstimate> forces;
  std::vector<MultiArmTruthSample> truths;
  if (!ReadForcesAndTruth(path, prefix, n_rotors, &forces, &truths, error)) return false;
  // A live log has them in arrival order: pair by stamp, each estimate
  // before the truth of its step, as the simulator emits them.
  const auto by_utime = [](const auto& a, const auto& b) { return a.utime < b.utime; };
  std::stable_sort(forces.begin(), forces.end(), by_utime);
  std::stable_sort(truths.begin(), truths.end(), by_utime);
  MultiArmAccuracyScorer scorer(n_rotors, options);
  size_t next_force = 0;
  for (const MultiArmTruthSample& truth : truths) {
    while (next_force < forces.size() && forces[next_force].utime <= truth.utime) {
      scorer.AddEstimate(forces[next_force++]);
    }
    scorer.AddTruth(truth);
  }
  *result = scorer.Finish();
  if (result->scored > 0) return true;
  *error = path + ": no " + prefix + "FORCE_N of " + std::to_string(n_rotors) + " rotors with a " + prefix +
           "TRUTH_N of its stamp (" + std::to_string(forces.size()) + " FORCE_N, " + std::to_string(truths.size()) +
           " TRUTH_N)";
  return false;
}

std::string MultiArmAccuracyHeader() {
  return "| scenario | method | MAE per rotor [N] | 2-sigma share per rotor | VALID share | step rotor | "
         "detection [ms] | false alarms | MISMATCH share |\n|---|---|---|---|---|---|---|---|---|\n";
}

std::string MultiArmAccuracyRow(const std::string& scenario, const std::string& method,
                                const MultiArmAccuracy& result) {
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
  row << "| " << scenario << " | " << method << " | "
      << joined([](const MultiArmRotorAccuracy& r) { return r.mae_n; }, 4) << " | "
      << joined([](const MultiArmRotorAccuracy& r) { return r.share_within_2sigma; }, 3) << " | " << result.valid_share
      << " | ";
  if (result.step_rotor > 0) {
    row.precision(1);
    row << result.step_rotor << " | " << result.detection_delay_s * 1e3 << " | ";
  } else {
    row << "- | - | ";
  }
  row.precision(3);
  row << result.false_alarms << " | " << result.mismatch_share << " |\n";
  return row.str();
}

}  // namespace birotor
