#include "estimator/input_admission.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace birotor {
namespace {

constexpr double kMicrosecond = 1e-6;
// A jump is also taken after this many times forward_jump_confirm_samples
// agreeing outliers in a row, for the case where a live input died at the
// jump and never confirms it (every sample would be an outlier forever).
constexpr int kDeadInputConfirmFactor = 10;

}  // namespace

const char* InputChannelName(InputChannel channel) {
  switch (channel) {
    case InputChannel::kStrain:
      return "STRAIN";
    case InputChannel::kMotor:
      return "MOTOR";
    case InputChannel::kImu:
      return "IMU";
    case InputChannel::kPose:
      return "POSE";
  }
  return "?";
}

InputAdmission::InputAdmission(const PipelineOptions& options)
    : options_(options),
      max_forward_jump_us_(static_cast<int64_t>(std::llround(options.max_forward_jump_s / kMicrosecond))) {}

Admission InputAdmission::Admit(InputChannel channel, int64_t utime, int32_t seq,
                                InputCounters inputs[kNumInputChannels]) {
  InputCounters* c = &inputs[static_cast<int>(channel)];
  if (utime < 0 || utime >= kMaxUtime) {
    ++c->rejected_invalid;
    return Admission::kInvalidStamp;
  }
  if (c->last_utime >= 0 && utime == c->last_utime) {
    ++c->duplicates;
    CountViolation(channel, c->last_utime, c);
    return Admission::kDuplicate;
  }
  if (c->last_utime >= 0 && utime < c->last_utime) {
    const double back_s = (c->last_utime - utime) * kMicrosecond;
    if (back_s <= options_.time_backwards_reset_s) {
      ++c->out_of_order;
      CountViolation(channel, c->last_utime, c);
      return Admission::kOutOfOrder;
    }
    Accept(channel, utime, seq, /*backwards_jump=*/true, c);
    return Admission::kAcceptedBackwardsJump;
  }
  if (IsTimeOutlier(channel, utime, inputs)) return Admission::kTimeOutlier;
  Accept(channel, utime, seq, /*backwards_jump=*/false, c);
  return Admission::kAccepted;
}

void InputAdmission::ClearJumpCandidate() {
  jump_candidate_utime_ = -1;
  jump_confirmations_ = 0;
  std::fill(std::begin(jumped_), std::end(jumped_), false);
}

bool InputAdmission::IsTimeOutlier(InputChannel channel, int64_t utime, InputCounters inputs[kNumInputChannels]) {
  if (newest_utime_ < 0 || utime - newest_utime_ <= max_forward_jump_us_) {
    ClearJumpCandidate();  // an in-bound sample: the present goes on
    return false;
  }
  // Ahead of every input. Consecutive outliers within the bound of each other
  // agree on one jump; it is a jump of every stream (a sender paused on a
  // wall clock) only when every live input (one that had a sample within the
  // bound of the newest) sent one of them, forward_jump_confirm_samples in
  // all. A burst on one channel, however many samples and however close
  // their stamps (issue 23: three sent 1 us apart), is not: the other inputs
  // go on in the present, and each of their samples starts the test again.
  if (jump_confirmations_ == 0 || std::abs(utime - jump_candidate_utime_) > max_forward_jump_us_) {
    ClearJumpCandidate();
  }
  ++jump_confirmations_;
  jump_candidate_utime_ = utime;
  jumped_[static_cast<int>(channel)] = true;
  bool every_live_input_jumped = true;
  for (int i = 0; i < kNumInputChannels; ++i) {
    const bool live = inputs[i].last_utime >= 0 && newest_utime_ - inputs[i].last_utime <= max_forward_jump_us_;
    if (live && !jumped_[i]) every_live_input_jumped = false;
  }
  const int needed = options_.forward_jump_confirm_samples;
  if ((every_live_input_jumped && jump_confirmations_ >= needed) ||
      jump_confirmations_ >= kDeadInputConfirmFactor * needed) {
    ClearJumpCandidate();
    return false;
  }
  ++inputs[static_cast<int>(channel)].time_outliers;
  return true;
}

void InputAdmission::Accept(InputChannel channel, int64_t utime, int32_t seq, bool backwards_jump, InputCounters* c) {
  if (c->last_utime >= 0 && !backwards_jump) {
    // seq wraps at int32: compare in unsigned arithmetic.
    const uint32_t expected = static_cast<uint32_t>(c->last_seq) + 1u;
    const int32_t jump = static_cast<int32_t>(static_cast<uint32_t>(seq) - expected);
    if (jump > 0) {
      ++c->gaps;
      c->missing_samples += jump;
    } else if (jump < 0) {
      CountViolation(channel, utime, c);  // seq went backwards with a newer stamp: a second sender?
    }
  }
  c->last_utime = utime;
  c->last_seq = seq;
  ++c->accepted_in_period;
  ConflictDetector& d = conflict_[static_cast<int>(channel)];
  if (c->conflict_active && (utime - d.last_violation_utime) * kMicrosecond > options_.conflict_clear_s) {
    c->conflict_active = false;
    d.count = 0;
  }
  // The strain clock is the estimator's: a strain stamp far behind the newest
  // (a first sample of another input stamped in the future) takes it back.
  const bool strain_far_behind =
      channel == InputChannel::kStrain && (newest_utime_ - utime) * kMicrosecond > options_.time_backwards_reset_s;
  if (backwards_jump || strain_far_behind || utime > newest_utime_) newest_utime_ = utime;
}

void InputAdmission::CountViolation(InputChannel channel, int64_t utime, InputCounters* c) {
  ConflictDetector& d = conflict_[static_cast<int>(channel)];
  const int needed = std::clamp(options_.conflict_min_violations, 2, kMaxConflictViolations);
  d.violation_utime[d.next] = utime;
  d.next = (d.next + 1) % kMaxConflictViolations;
  d.count = std::min(d.count + 1, kMaxConflictViolations);
  d.last_violation_utime = utime;
  if (c->conflict_active || d.count < needed) return;
  // The needed-th newest violation, within the window of this one?
  const int64_t oldest = d.violation_utime[(d.next - needed + 2 * kMaxConflictViolations) % kMaxConflictViolations];
  if ((utime - oldest) * kMicrosecond <= options_.conflict_window_s) {
    c->conflict_active = true;
    ++c->conflicts;
  }
}

bool InputAdmission::AnyConflictActive(const InputCounters inputs[kNumInputChannels]) {
  for (InputChannel channel : {InputChannel::kStrain, InputChannel::kMotor, InputChannel::kImu}) {
    if (inputs[static_cast<int>(channel)].conflict_active) return true;
  }
  return false;
}

}  // namespace birotor
