// The estimator's input path, shared by the live daemon and the replay tool so
// both give the same numbers: validates every sample (finite fields, time
// order, duplicates, seq gaps), calibrates the strain gauges (scale, and the
// offset from the parameters or a tare on the ground: gauge_tare.h), detects
// stale inputs and long gaps, resets the method after a gap or a backwards
// time jump, rejects time outliers, detects conflicting publishers, and keeps
// the health counters published on ESTIMATOR_STATUS (per input, from the
// method's fusion reports). No LCM and no logging here (nodes/ logs from
// the counters); no allocation per sample.
#pragma once

#include <cstdint>
#include <memory>

#include "estimator/estimator_config.h"
#include "estimator/force_estimator.h"
#include "estimator/gauge_calibration.h"
#include "estimator/gauge_tare.h"
#include "estimator/harmonic_notch.h"
#include "estimator/model_consistency.h"
#include "estimator/motor_speed_tracker.h"
#include "samples/samples.h"

namespace birotor {

enum class InputChannel : int { kStrain = 0, kMotor = 1, kImu = 2, kPose = 3 };
constexpr int kNumInputChannels = 4;
const char* InputChannelName(InputChannel channel);  // "STRAIN", "MOTOR", "IMU", "POSE"
// The input a measurement comes from (strain: STRAIN, telemetry: MOTOR, gyro: IMU).
InputChannel InputChannelOf(FusionSource source);

// Counters for one input since start-up (fields as in lcmtypes/input_health_t.lcm).
struct InputCounters {
  int64_t received = 0;  // every packet, good or bad (CountReceived)
  // Per FusionReport of this input's measurements (see FusionOutcome).
  int64_t fused = 0;
  int64_t rejected_gate = 0;
  int64_t not_fused = 0;
  int64_t rejected_invalid = 0;  // non-finite / out-of-range fields
  int64_t decode_errors = 0;     // CountDecodeError
  int64_t out_of_order = 0;      // utime older than the newest accepted
  int64_t duplicates = 0;        // utime equal to the newest accepted
  int64_t time_outliers = 0;     // utime too far ahead of every input (PipelineOptions::max_forward_jump_s)
  int64_t gaps = 0;              // forward seq jumps
  int64_t missing_samples = 0;   // sum of jump sizes
  int64_t dropped_overload = 0;  // CountOverloadDrop
  int64_t reading_missing = 0;   // accepted samples with a NaN optional reading (MOTOR telemetry, IMU accelerometer)
  int64_t conflicts = 0;         // conflicting-publisher detections
  bool conflict_active = false;  // a conflict is in effect (cleared after conflict_clear_s)
  int64_t last_utime = -1;       // newest accepted sample [us]; -1 if none
  int32_t last_seq = 0;
  double gate = 0;  // this input's NIS gate; NaN if the method has none
  // Over the current period (cleared by TakePeriod()):
  int64_t accepted_in_period = 0;  // for rate_hz
  double nis_sum = 0;              // NIS of the reports that carry one
  double nis_max = 0;
  int64_t nis_count = 0;
};

struct PipelineHealth {
  InputCounters inputs[kNumInputChannels];
  // The IMU's a_z as a measurement of its own (the EKF fuses it in flight):
  // received = accepted IMU samples with a finite a_z, the fusion counters
  // and NIS of its reports, its gate; the other fields stay 0.
  InputCounters accelerometer;
  // Newest accepted sample time over all inputs [us] (time outliers are not
  // accepted; a STRAIN stamp more than time_backwards_reset_s behind it resets it).
  int64_t newest_utime = -1;
  // Re-initialisations; the first strain sample counts as one (kStart).
  int64_t resets = 0;
  ResetReason last_reset_reason = ResetReason::kNone;
  int64_t published = 0;  // force estimates produced
  int32_t last_status = 0;
  ForceEstimate last_estimate;
  // Strain-gauge calibration: the scale in use and the offsets o_i as now
  // known (the calibration the method is given, from the file, a tare or
  // the state file, plus what the method learned in flight, with its sigma;
  // the daemon persists these), and the tare's counters.
  GaugeCalibration gauge;
  TareCounters tare;
  // Model consistency (issue 27): STATUS_MODEL_MISMATCH and its statistic.
  ModelConsistencyState consistency;
};

class EstimatorPipeline : private FusionReportSink {
 public:
  explicit EstimatorPipeline(const EstimatorConfig& config);
  ~EstimatorPipeline() override;
  EstimatorPipeline(const EstimatorPipeline&) = delete;
  EstimatorPipeline& operator=(const EstimatorPipeline&) = delete;

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
  // Conflicting-publisher detector of one input: the stream clocks of its
  // newest order violations.
  static constexpr int kMaxConflictViolations = 16;
  struct ConflictDetector {
    int64_t violation_utime[kMaxConflictViolations] = {};
    int next = 0;   // ring slot of the next violation
    int count = 0;  // violations in the ring
    int64_t last_violation_utime = -1;
  };

  enum class TimeOrder { kInOrder, kDuplicate, kOutOfOrder, kBackwardsJump };
  // Classifies utime against the newest accepted sample of the channel.
  TimeOrder CheckTime(const InputCounters& counters, int64_t utime) const;
  // True (and counted) when utime is a time outlier: too far ahead of every
  // input and not yet confirmed as a jump of every stream.
  bool IsTimeOutlier(InputCounters* counters, int64_t utime);
  // Drops and counts outliers, duplicate and out-of-order samples (false);
  // otherwise accepts the sample and says whether it jumped back in time.
  bool Admit(InputChannel channel, int64_t utime, int32_t seq, bool* backwards_jump);
  // Accepts a sample: seq gap book-keeping, last_utime/last_seq, rates.
  void Accept(InputChannel channel, int64_t utime, int32_t seq, bool backwards_jump);
  // An order violation at the channel's stream time utime (conflict detection).
  void CountViolation(InputChannel channel, int64_t utime);
  bool AnyConflictActive() const;
  // Re-initialises the method and re-feeds the newest motor command (without
  // its telemetry) if it is still current at utime.
  void ResetMethod(ResetReason reason, int64_t utime);
  // Gives the method a new calibration offset (file, tare, state file, or
  // what it learned before a reset) and reports it.
  void UseGaugeOffsets(const double offset_rad[2], const double offset_std_rad[2], GaugeOffsetSource source);
  // health_.gauge = calibration_ + what the method learned (scaled to the raw reading).
  void UpdateReportedGaugeOffsets();
  void OnFusion(const FusionReport& report) override;

  EstimatorConfig config_;
  std::unique_ptr<ForceEstimator> method_;
  GaugeCalibration calibration_;  // applied to every strain reading: b = (b_meas - o) / s
  PipelineHealth health_;
  GaugeTare tare_;
  MotorSpeedTracker rotor_speed_;  // for the harmonic notches
  HarmonicNotch notch_;
  ModelConsistencyMonitor consistency_;  // judges every fusion report (docs/mismatch.md)
  ConflictDetector conflict_[kNumInputChannels];
  int64_t max_forward_jump_us_ = 0;
  int64_t jump_candidate_utime_ = -1;  // stamp of the newest time outlier [us]
  int jump_confirmations_ = 0;         // consecutive outliers agreeing with it

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

// The NIS gate of each input's measurements for config.method; NaN where the
// method has no gate (the baselines, POSE).
double GateOf(const EstimatorConfig& config, InputChannel channel);

}  // namespace birotor
