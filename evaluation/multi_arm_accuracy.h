// Accuracy of the N-arm estimator (estimator/multi_arm_pipeline.h around the
// method of estimator.method: the daemon's code) against the truth of
// the N-arm simulator, run in-process and lock-step: MultiArmSimulator emits
// each sample straight into it (birotor-eval --vehicle FILE); or of the
// FORCE_N and TRUTH_N of a log (birotor-eval --vehicle FILE --log LOG: a
// live run recorded by lcm-logger, or birotor-replay --vehicle's output). Per
// rotor the MAE and the share of errors within 2 sigma, the shares of VALID
// and of MODEL_MISMATCH estimates, and for a scenario with a thrust step the time from the step to
// the stepped rotor's fault flag and the false alarms. docs/estimator.md,
// "The EKF for N arms".
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "estimator/estimator_config.h"
#include "evaluation/eval_metrics.h"
#include "model/vehicle_description.h"
#include "samples/multi_arm_samples.h"
#include "simulator/scenario.h"

namespace birotor {

struct MultiArmRotorAccuracy {
  int64_t count = 0;               // scored estimates
  double mae_n = 0;                // mean |f_est - f_true| [N]
  double share_within_2sigma = 0;  // share with |error| <= 2 force_std_n [1]
};

struct MultiArmAccuracy {
  int n_rotors = 0;
  std::array<MultiArmRotorAccuracy, kMaxArms> rotor{};
  int64_t scored = 0;      // estimates paired with the truth of their utime, after the warm-up
  int64_t nonfinite = 0;   // estimates with a NaN/Inf force or sigma
  double valid_share = 0;  // share of scored estimates with STATUS_VALID [1]
  // Share of scored estimates with STATUS_MODEL_MISMATCH (the pipeline's
  // model-consistency monitor, docs/mismatch.md) [1].
  double mismatch_share = 0;
  // First thrust-scale step in truth (EvalOptions::step_threshold): rotor
  // 1-based (0: none), its time since the first truth sample [s], and the
  // delay to the first estimate flagging that rotor at or after it (NaN if never) [s].
  int step_rotor = 0;
  double step_time_s = 0;
  double detection_delay_s = 0;
  // Estimates flagging rotor i while its true thrust scale is above
  // EvalOptions::false_alarm_truth_scale (one per rotor and estimate).
  int64_t false_alarms = 0;
  // A flight with a ground phase is scored from its lift-off (the birotor
  // eval's rule); the estimates before it are counted here: all, and the
  // VALID ones with some rotor more than 3 sigma off the truth.
  int64_t before_liftoff = 0;
  int64_t before_liftoff_valid_beyond_3sigma = 0;
};

// Scores estimates against the truth of their utime: each estimate is
// paired with the next truth if their stamps are equal (the order the
// simulator emits them: STRAIN_N, then TRUTH_N of the same step), with
// options' warmup_s, step_threshold and false_alarm_truth_scale.
class MultiArmAccuracyScorer {
 public:
  MultiArmAccuracyScorer(int n_rotors, const EvalOptions& options);
  void AddEstimate(const MultiArmForceEstimate& estimate);
  void AddTruth(const MultiArmTruthSample& truth);
  // Estimates stamped before utime [us] are not scored but counted as
  // before lift-off (options' score_from_utime until called).
  void SetScoreFrom(int64_t utime) { score_from_utime_ = utime; }
  MultiArmAccuracy Finish() const;

 private:
  void DetectStep(const MultiArmTruthSample& truth);
  void Score(const MultiArmForceEstimate& e, const MultiArmTruthSample& truth);

  int n_;
  EvalOptions options_;
  MultiArmAccuracy result_;
  MultiArmForceEstimate pending_;
  bool has_pending_ = false;
  int64_t score_from_utime_;
  int64_t first_estimate_utime_ = -1, first_truth_utime_ = -1, step_utime_ = 0, valid_count_ = 0, mismatch_count_ = 0;
  ArmValues last_truth_scale_{};
  bool has_last_truth_ = false;
  std::array<double, kMaxArms> abs_sum_{};
  std::array<int64_t, kMaxArms> within_{};
};

// Simulates the scenario on the vehicle (MultiArmSimulator) and feeds every
// (with a ground phase, scored from the simulator's lift-off)
// STRAIN_N, MOTOR_N, IMU and POSE sample to a MultiArmPipeline of estimator
// (its method and sections, the vehicle replaced) as it is emitted. Throws
// std::invalid_argument as MultiArmSimulator does (a scenario the vehicle
// cannot fly).
MultiArmAccuracy RunMultiArmAccuracy(const VehicleDescription& vehicle, const Scenario& scenario,
                                     const EstimatorConfig& estimator, const EvalOptions& options);
// The same with the simulator flying `flown` and the estimator running on
// estimator.vehicle, its description (the same arm count): a vehicle that
// differs from its file (a payload, a stiffer arm). Throws
// std::invalid_argument for another arm count.
MultiArmAccuracy RunMultiArmAccuracyFlying(const VehicleDescription& flown, const Scenario& scenario,
                                           const EstimatorConfig& estimator, const EvalOptions& options);

// The FORCE_N of the log at path (channel prefix) against its TRUTH_N, paired
// by utime. False with a one-line *error when the log cannot be read or
// holds no FORCE_N with a TRUTH_N of its stamp; a message of another count
// than n_rotors is not scored.
bool ScoreMultiArmLog(const std::string& path, const std::string& prefix, int n_rotors, const EvalOptions& options,
                      MultiArmAccuracy* result, std::string* error);

// Markdown: one header, one row per scenario and method (rotors as columns
// "r1 / r2 / .."; method: the estimator.method name, or FORCE_N for a log).
std::string MultiArmAccuracyHeader();
std::string MultiArmAccuracyRow(const std::string& scenario, const std::string& method, const MultiArmAccuracy& result);

}  // namespace birotor
