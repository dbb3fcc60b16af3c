// What the controller does with SETPOINT: each setpoint checked (finite,
// stamp within the controller's clock windows, within the position and
// feed-forward bounds, no jump from the reference flown now, not faster than
// the rate limit) and counted; the newest accepted one followed (extrapolated
// with its own feed-forward for at most max_extrapolation_s), held for
// timeout_s, then the vehicle hovers where it is. Before any setpoint it
// holds the start position (the first POSE). No allocation, no throw.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "controller/controller_params.h"
#include "controller/reference_point.h"
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
};

class SetpointInput {
 public:
  explicit SetpointInput(const SetpointParams& params) : params_(params) {}

  // The position held before any setpoint (the first POSE).
  void SetStart(const Eigen::Vector2d& position_m);
  // One setpoint, arrived when the controller's clock read now_us [us].
  // Returns true when accepted.
  bool Offer(const Setpoint& setpoint, int64_t now_us);
  // The reference at now_us; position_m is where the vehicle is (the hover
  // point when the setpoint times out now).
  ReferencePoint At(int64_t now_us, const Eigen::Vector2d& position_m);

  SetpointState state() const { return state_; }
  const SetpointCounters& counters() const { return counters_; }
  // Newest accepted setpoint's stamp [us]; -1 before any.
  int64_t last_utime() const { return has_setpoint_ ? newest_.utime : -1; }

 private:
  bool Plausible(const Setpoint& s) const;

  SetpointParams params_;
  SetpointState state_ = SetpointState::kHoldStart;
  SetpointCounters counters_;
  bool has_setpoint_ = false;
  Setpoint newest_;
  Eigen::Vector2d hold_m_ = Eigen::Vector2d::Zero();  // start or hover point
  ReferencePoint last_reference_;                     // the reference flown at the last At()
};

}  // namespace birotor
