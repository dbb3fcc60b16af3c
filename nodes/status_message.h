// Building the ESTIMATOR_STATUS health message (lcmtypes/estimator_status_t.lcm)
// from the pipeline's counters, and the fixed-size statistics of per-sample
// processing time that go into it. Shared by the daemon and birotor-replay.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "birotor/estimator_status_t.hpp"
#include "estimator/estimator_pipeline.h"
#include "estimator/multi_arm_pipeline.h"
#include "transport/udpm_receiver.h"

namespace birotor {

// Mean, 99th percentile and maximum of per-sample processing times [us] over
// one reporting period. Add() is allocation-free (fixed ring of the most
// recent kCapacity samples); the percentile is computed at report time only.
class ProcessingTimeStats {
 public:
  static constexpr int kCapacity = 16384;  // > 1 s of samples at 10 kHz

  void Add(double time_us);
  // Statistics since the last TakePeriod(); NaN when no sample was added.
  double MeanUs() const;
  double MaxUs() const;
  // Over the newest min(count, kCapacity) samples of the period.
  double P99Us();
  void TakePeriod();
  int64_t count() const { return count_; }

 private:
  std::array<double, kCapacity> ring_{};
  std::array<double, kCapacity> scratch_{};
  int next_ = 0;       // ring index the next sample goes to
  int64_t count_ = 0;  // samples in the current period
  double sum_us_ = 0;
  double max_us_ = 0;
};

// Inputs of one status message besides the pipeline's counters.
struct StatusContext {
  int64_t wall_utime = 0;              // host clock at publication [us since epoch]
  int32_t seq = 0;                     // status message counter
  double period_s = 0;                 // length of the reporting period, for rate_hz [s]
  double processing_time_mean_us = 0;  // NaN when not measured
  double processing_time_p99_us = 0;
  double processing_time_max_us = 0;
  UdpReceiveCounters udp;             // the daemon's UDP reader; zeros without one
  const char* vehicle_checksum = "";  // VehicleChecksum of the configured vehicle (gauge_state_file.h)
};

// Where a learned vehicle parameter of ESTIMATOR_STATUS comes from
// (strain_scale_source, body_mass_source).
inline constexpr const char* kLearnedSourceParams = "params";         // not learned: the file's value
inline constexpr const char* kLearnedSourceLearned = "learned";       // learned in this run from the file's value
inline constexpr const char* kLearnedSourceStateFile = "state_file";  // learned from an earlier run's value

// The source of the strain scales in use: params (not learned), learned, or
// state_file (learning started from the gauge state file's value).
const char* StrainScaleSource(const PipelineHealth& health);

// Fills *message from the pipeline's health (per-input counters in the order
// STRAIN, MOTOR, IMU, POSE; age_s on the vehicle clock relative to the newest
// sample of any input; rates from accepted_in_period / period_s; NIS mean and
// max per input over the period, and its gate; strain_nis_* and strain_gate
// repeat the STRAIN input's; the learned strain scales and body mass with
// their sigma, NaN and the file's value when not learned). Reuses the message's vectors, so steady state does not
// allocate.
void BuildStatusMessage(const PipelineHealth& health, const char* method, const StatusContext& context,
                        estimator_status_t* message);

// The same for the N-arm pipeline (birotor-estimator --vehicle): the
// per-input counters (the fusion counters and NIS from the method's reports,
// the accelerometer's of its own), resets, the newest status, the method's
// name (estimator.method); the birotor's two-element
// fields (forces, thrust scales, gauge offsets, strain scales) and the body
// mass NaN: the forces and efficiencies are on FORCE_N.
void BuildMultiArmStatusMessage(const MultiArmPipelineHealth& health, const char* method, const StatusContext& context,
                                estimator_status_t* message);

// The newest ESTIMATOR_STATUS on `channel` of the LCM log at log_path that
// carries a learned value (strain_scale_source or body_mass_source other
// than "params"), for `birotor-identify --learned LOG`. False with a
// one-line *error naming the file when it is not a readable log or has no
// such message (learning off, or another prefix).
bool ReadLastLearnedStatus(const std::string& log_path, const std::string& channel, estimator_status_t* status,
                           std::string* error);

}  // namespace birotor
