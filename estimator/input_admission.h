// Admission of every input sample by its stamp and sequence number, before
// any method sees it: stamps out of range, duplicates, out-of-order samples,
// time outliers (a stamp too far ahead of every input, unless every live input
// jumped there together), backwards jumps (a log loop), seq gaps, and
// conflicting publishers (order violations in a burst). It keeps the per-input
// counters of ESTIMATOR_STATUS and the newest accepted stamp; it knows nothing
// of the samples' readings or of the method. No allocation, no throw, no log.
#pragma once

#include <cstdint>

#include "estimator/estimator_config.h"

namespace birotor {

enum class InputChannel : int { kStrain = 0, kMotor = 1, kImu = 2, kPose = 3 };
constexpr int kNumInputChannels = 4;
const char* InputChannelName(InputChannel channel);  // "STRAIN", "MOTOR", "IMU", "POSE"

// Counters for one input since start-up (fields as in lcmtypes/input_health_t.lcm).
struct InputCounters {
  int64_t received = 0;  // every packet, good or bad (CountReceived)
  // Per FusionReport of this input's measurements (see FusionOutcome).
  int64_t fused = 0;
  int64_t rejected_gate = 0;
  int64_t not_fused = 0;
  int64_t rejected_invalid = 0;  // non-finite / out-of-range fields or stamp
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

// What admission decided about one sample.
enum class Admission : int {
  kAccepted = 0,
  kAcceptedBackwardsJump,  // accepted; it jumped back more than time_backwards_reset_s (a log loop)
  kInvalidStamp,           // negative or >= 2^53 us (rejected_invalid)
  kDuplicate,              // stamp equal to the channel's newest (duplicates)
  kOutOfOrder,             // older than the channel's newest (out_of_order)
  kTimeOutlier,            // too far ahead of every input (time_outliers)
};
inline bool IsAccepted(Admission a) { return a == Admission::kAccepted || a == Admission::kAcceptedBackwardsJump; }

class InputAdmission {
 public:
  // Stamps are microseconds on the vehicle clock: never negative, and below
  // 2^53 us (285 years) so that every difference of two stamps is exact in a
  // double and cannot overflow int64.
  static constexpr int64_t kMaxUtime = int64_t{1} << 53;

  explicit InputAdmission(const PipelineOptions& options);

  // Decides on a sample of `channel` stamped utime with sequence number seq,
  // counting it in inputs[channel] (the array of all kNumInputChannels
  // counters: the outlier rule looks at every input). An accepted sample
  // becomes the channel's newest (last_utime, last_seq, seq gaps counted).
  Admission Admit(InputChannel channel, int64_t utime, int32_t seq, InputCounters inputs[kNumInputChannels]);

  // Newest accepted stamp over all inputs [us]; -1 before the first. Time
  // outliers never move it; a STRAIN stamp more than time_backwards_reset_s
  // behind it takes it back (the strain clock is the estimator's).
  int64_t newest_utime() const { return newest_utime_; }
  // A conflict in effect on STRAIN, MOTOR or IMU (POSE is used by no method:
  // counted there, not flagged).
  static bool AnyConflictActive(const InputCounters inputs[kNumInputChannels]);

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

  // True (and counted) when utime is a time outlier: too far ahead of every
  // input and not yet confirmed as a jump of every live stream.
  bool IsTimeOutlier(InputChannel channel, int64_t utime, InputCounters inputs[kNumInputChannels]);
  void ClearJumpCandidate();
  void Accept(InputChannel channel, int64_t utime, int32_t seq, bool backwards_jump, InputCounters* c);
  // An order violation at the channel's stream time utime (conflict detection).
  void CountViolation(InputChannel channel, int64_t utime, InputCounters* c);

  PipelineOptions options_;
  int64_t max_forward_jump_us_;
  int64_t newest_utime_ = -1;
  ConflictDetector conflict_[kNumInputChannels];
  // The forward jump under test: the newest outlier's stamp, how many
  // consecutive outliers agreed on it (within max_forward_jump_s of each
  // other, no in-bound sample between), and which inputs sent one.
  int64_t jump_candidate_utime_ = -1;
  int jump_confirmations_ = 0;
  bool jumped_[kNumInputChannels] = {};
};

}  // namespace birotor
