// What the controller does with SETPOINT: each setpoint checked (finite,
// stamp within the controller's clock windows, within the position and
// feed-forward bounds, from the one locked publisher, not faster than the
// rate limit, no jump from the reference flown now, feed-forward consistent
// with the change of position) and counted; the newest accepted one followed
// (extrapolated with its own feed-forward for at most max_extrapolation_s),
// held for timeout_s, then the vehicle hovers where it is. Before any
// setpoint it holds the start position (the first POSE); while two
// publishers conflict it holds the reference flown then. Whatever the target,
// the reference flown moves within max_speed_m_s and max_accel_m_s2
// (ReferenceShaper). No allocation, no throw.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "controller/controller_params.h"
#include "controller/reference_point.h"
#include "controller/reference_shaper.h"
#include "controller/setpoint_publisher_lock.h"
#include "samples/setpoint.h"

namespace birotor {

// Where the reference comes from (controller_status_t SETPOINT_*).
enum class SetpointState : int32_t {
  kHoldStart = 0,  // no setpoint yet: hold the start position
  kFollowing = 1,  // the newest setpoint is younger than timeout_s
  kHoldHere = 2,   // it timed out: hover where the vehicle was then
};

struct SetpointCounters {
  int64_t received = 0;
  int64_t accepted = 0;
  int64_t rejected_invalid = 0;       // non-finite position, or position/feed-forward beyond the bounds
  int64_t rejected_stamp = 0;         // stamp outside [now - timeout_s, now + future_window_s]
  int64_t rejected_out_of_order = 0;  // stamp not newer than the newest accepted
  int64_t rejected_rate = 0;          // stamp closer than min_interval_s to the newest accepted
  int64_t rejected_jump = 0;          // position farther than max_jump_m from the reference flown now
  int64_t timeouts = 0;               // entries into kHoldHere
  int64_t rejected_inconsistent = 0;  // feed-forward disagrees with the change of position (or of velocity)
  int64_t rejected_conflict = 0;      // refused while two publishers conflict (both publishers' messages)
  int64_t conflicts = 0;              // entries into a publisher conflict
  int64_t limited_periods = 0;        // periods the reference was shaped by the speed/acceleration limits
};

// The limits and the lock rule of SetpointParams.
ShaperLimits ShaperLimitsOf(const SetpointParams& params);
PublisherLockRule PublisherLockRuleOf(const SetpointParams& params);

class SetpointInput {
 public:
  explicit SetpointInput(const SetpointParams& params)
      : params_(params), shaper_(ShaperLimitsOf(params)), lock_(PublisherLockRuleOf(params)) {}

  // The position held before any setpoint (the first POSE).
  void SetStart(const Eigen::Vector2d& position_m);
  // One setpoint, arrived when the controller's clock read now_us [us].
  // Returns true when accepted.
  bool Offer(const Setpoint& setpoint, int64_t now_us);
  // The reference flown at now_us (once per control period); position_m is
  // where the vehicle is (the hover point when the setpoint times out now).
  ReferencePoint At(int64_t now_us, const Eigen::Vector2d& position_m);

  SetpointState state() const { return state_; }
  SetpointCounters counters() const;
  // Newest accepted setpoint's stamp [us]; -1 before any.
  int64_t last_utime() const { return has_setpoint_ ? newest_.utime : -1; }

 private:
  bool Plausible(const Setpoint& s) const;
  // Stamp window, lock, order, rate: counts and returns false on a refusal.
  bool InTimeFromTheLockedPublisher(const Setpoint& s, int64_t now_us);
  // |v_ff - dp/dt| and |a_ff - dv/dt| against the newest accepted setpoint.
  bool FeedForwardConsistent(const Setpoint& s) const;
  // The unshaped reference at now_us (the newest setpoint, a hold point).
  ReferencePoint Target(int64_t now_us, const Eigen::Vector2d& position_m);

  SetpointParams params_;
  SetpointState state_ = SetpointState::kHoldStart;
  SetpointCounters counters_;
  bool has_setpoint_ = false;
  Setpoint newest_;
  Eigen::Vector2d hold_m_ = Eigen::Vector2d::Zero();  // start or hover point
  ReferenceShaper shaper_;                            // holds the reference flown at the last At()
  int64_t last_at_us_ = -1;                           // clock of the last At() [us]; -1 before any
  bool started_ = false;                              // SetStart came
  SetpointPublisherLock lock_;
  bool holding_for_conflict_ = false;
  Eigen::Vector2d conflict_hold_m_ = Eigen::Vector2d::Zero();  // reference flown when the conflict began
};

}  // namespace birotor
