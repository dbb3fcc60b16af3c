// The estimator's input path, shared by the live daemon and the replay tool so
// both give the same numbers: validates every sample (finite fields, time
// order, duplicates, seq gaps), calibrates the strain gauges (scale, and the
// offset from the parameters or a tare on the ground: gauge_tare.h), detects
// stale inputs and long gaps, resets the
// method after a gap or a backwards time jump, and keeps the health counters
// published on ESTIMATOR_STATUS. No LCM here; no allocation per sample.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "estimator/estimator_config.h"
#include "estimator/force_estimator.h"
#include "estimator/gauge_calibration.h"
#include "estimator/gauge_tare.h"
#include "estimator/harmonic_notch.h"
#include "estimator/motor_speed_tracker.h"
#include "estimator/samples.h"

namespace birotor {

enum class InputChannel : int { kStrain = 0, kMotor = 1, kImu = 2, kPose = 3 };
constexpr int kNumInputChannels = 4;
const char* InputChannelName(InputChannel channel);  // "STRAIN", "MOTOR", "IMU", "POSE"

// Counters for one input since start-up (fields as in lcmtypes/input_health_t.lcm).
struct InputCounters {
  int64_t received = 0;  // every packet, good or bad (CountReceived)
  int64_t fused = 0;
  int64_t rejected_gate = 0;
  int64_t rejected_invalid = 0;   // non-finite / out-of-range fields
  int64_t decode_errors = 0;      // CountDecodeError
  int64_t out_of_order = 0;       // utime older than the newest accepted
  int64_t duplicates = 0;         // utime equal to the newest accepted
  int64_t gaps = 0;               // forward seq jumps
  int64_t missing_samples = 0;    // sum of jump sizes
  int64_t dropped_overload = 0;   // CountOverloadDrop
  int64_t telemetry_missing = 0;  // MOTOR only: accepted samples with a NaN omega_meas
  int64_t last_utime = -1;        // newest accepted sample [us]; -1 if none
  int32_t last_seq = 0;
  int64_t accepted_in_period = 0;  // for rate_hz; cleared by TakePeriod()
};

struct PipelineHealth {
  InputCounters inputs[kNumInputChannels];
  int64_t newest_utime = -1;  // newest sample time over all inputs [us]
  int64_t resets = 0;
  // "start" (the first strain sample counts as a reset), "gap",
  // "time_backwards", "numerical"; empty before any.
  std::string last_reset_reason;
  int64_t published = 0;  // force estimates produced
  int32_t last_status = 0;
  ForceEstimate last_estimate;
  // Strain NIS over the current period (cleared by TakePeriod()).
  double nis_sum = 0;
  double nis_max = 0;
  int64_t nis_count = 0;
  // Strain-gauge calibration in use (every method sees (b_meas - o) / s) and
  // the tare's counters.
  GaugeCalibration gauge;
  TareCounters tare;
};

class EstimatorPipeline {
 public:
  explicit EstimatorPipeline(const EstimatorConfig& config);
  ~EstimatorPipeline();

  // Book-keeping for packets seen by the transport layer.
  void CountReceived(InputChannel channel);
  void CountDecodeError(InputChannel channel);
  void CountOverloadDrop(InputChannel channel);

  void OnMotor(const MotorSample& sample);
  void OnImu(const ImuSample& sample);
  void OnPose(const PoseSample& sample);
  // Returns true and fills *estimate when a FORCE message must be published
  // (one per accepted strain sample; never NaN: invalid estimates carry
  // status without kStatusValid and the last finite values).
  bool OnStrain(const StrainSample& sample, ForceEstimate* estimate);

  const PipelineHealth& health() const { return health_; }
  // Replaces the gauge offsets in use (e.g. from the persisted state file);
  // the scale stays the parameter file's. A later tare replaces them again.
  void SetGaugeOffsets(const GaugeCalibration& calibration);
  // Clears the per-period fields (rates, NIS) after a status message.
  void TakePeriod();
  const char* method_name() const;
  const EstimatorConfig& config() const { return config_; }

 private:
  EstimatorConfig config_;
  std::unique_ptr<ForceEstimator> method_;
  PipelineHealth health_;
  GaugeTare tare_;
  MotorSpeedTracker rotor_speed_;  // for the harmonic notches
  HarmonicNotch notch_;

  enum class TimeOrder { kInOrder, kDuplicate, kOutOfOrder, kBackwardsJump };
  // Classifies utime against the newest accepted sample of the channel.
  TimeOrder CheckTime(const InputCounters& counters, int64_t utime) const;
  // Drops and counts duplicate and out-of-order samples (false); otherwise
  // accepts the sample and says whether it jumped back in time.
  bool Admit(InputCounters* counters, int64_t utime, int32_t seq, bool* backwards_jump);
  // Accepts a sample: seq gap book-keeping, last_utime/last_seq, rates.
  void Accept(InputCounters* counters, int64_t utime, int32_t seq, bool backwards_jump);
  // Re-initialises the method and re-feeds the newest motor command if it is
  // still current at utime. reason must be a string literal.
  void ResetMethod(const char* reason, int64_t utime);

  bool started_ = false;             // a strain sample has been accepted
  bool reset_flag_pending_ = false;  // kStatusFilterReset on the next estimate
  bool has_motor_ = false;
  MotorSample last_motor_;
  bool has_finite_estimate_ = false;
  ForceEstimate last_finite_estimate_;
};

// Creates the method named in config.method (EstimationMethodNames());
// nullptr for an unknown name (the EstimatorPipeline constructor then throws
// std::invalid_argument; the config loader refuses such names earlier).
std::unique_ptr<ForceEstimator> MakeForceEstimator(const EstimatorConfig& config);

}  // namespace birotor
