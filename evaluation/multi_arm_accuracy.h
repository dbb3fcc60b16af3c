// Accuracy of the N-arm EKF (estimator/multi_arm_ekf.h) against the truth of
// the N-arm simulator, run in-process and lock-step: MultiArmSimulator emits
// each sample straight into the filter (birotor-eval --vehicle FILE). Per
// rotor the MAE and the share of errors within 2 sigma, the share of VALID
// estimates, and for a scenario with a thrust step the time from the step to
// the stepped rotor's fault flag and the false alarms. docs/estimator.md,
// "The EKF for N arms".
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "estimator/estimator_config.h"
#include "evaluation/eval_metrics.h"
#include "model/vehicle_description.h"
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
  // First thrust-scale step in truth (EvalOptions::step_threshold): rotor
  // 1-based (0: none), its time since the first truth sample [s], and the
  // delay to the first estimate flagging that rotor at or after it (NaN if never) [s].
  int step_rotor = 0;
  double step_time_s = 0;
  double detection_delay_s = 0;
  // Estimates flagging rotor i while its true thrust scale is above
  // EvalOptions::false_alarm_truth_scale (one per rotor and estimate).
  int64_t false_alarms = 0;
};

// Simulates the scenario on the vehicle (MultiArmSimulator) and feeds every
// STRAIN_N, MOTOR_N and IMU sample to MakeMultiArmEkf(vehicle, ekf) as it is
// emitted; scores with options' warmup_s, step_threshold and
// false_alarm_truth_scale. Throws std::invalid_argument as MultiArmSimulator
// does (a scenario the vehicle cannot fly).
MultiArmAccuracy RunMultiArmAccuracy(const VehicleDescription& vehicle, const Scenario& scenario, const EkfOptions& ekf,
                                     const EvalOptions& options);

// Markdown: one header, one row per scenario (rotors as columns "r1 / r2 / ..").
std::string MultiArmAccuracyHeader();
std::string MultiArmAccuracyRow(const std::string& scenario, const MultiArmAccuracy& result);

}  // namespace birotor
