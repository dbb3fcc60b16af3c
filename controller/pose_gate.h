// The controller's POSE innovation gate (issue 23, issue 34): a POSE far
// from the controller's own observer is refused, unless the vehicle really
// is there. Two ways back: every POSE refused for pose_gate_reset_s (the
// observer is re-initialised on the next), or a run of pose_reacquire_count
// refused POSEs that agree with each other and with the IMU (each within
// pose_reacquire_position_m / _angle_rad of the previous one moved on by the
// observer's velocity and pitch rate): a re-acquisition, the observer moved
// onto the newest. A single outlier, or an attacker's stream interleaved
// with the real one, breaks the run. No allocation, no throw.
#pragma once

#include <cstdint>

#include "controller/body_state_observer.h"
#include "controller/controller_params.h"
#include "controller/position_attitude_law.h"
#include "samples/samples.h"

namespace birotor {

class PoseGate {
 public:
  enum class Verdict {
    kInside,      // within the gate: fuse
    kRefused,     // outside: refused and counted
    kReset,       // outside, but every POSE has been for pose_gate_reset_s: re-initialise
    kReacquired,  // outside, but a consistent run: move the observer onto it
  };

  explicit PoseGate(const SupervisionParams& params) : params_(params) {}

  // A finite POSE against the observer's state, arrived at now_us [us].
  Verdict Check(const PoseSample& sample, const BodyState& observer, int64_t now_us);

 private:
  // The sample is where the previous refused one and the observer's
  // velocity and pitch rate put it.
  bool ContinuesRun(const PoseSample& sample, const BodyState& observer) const;

  SupervisionParams params_;
  int64_t gated_since_us_ = -1;  // first refusal of the current run of refusals; -1 if none
  int run_ = 0;                  // consistent refused POSEs in a row
  PoseSample previous_;          // the newest refused POSE
};

// What both controllers do with a POSE the gate let through from outside it
// (kReset: every POSE refused for pose_gate_reset_s, the observer is
// re-initialised there; kReacquired: a consistent run, the position drifted
// and the IMU's velocity and rate did not, so the observer is relocated).
// True when the observer was moved (the POSE is used, not held for fusion).
bool MoveObserverOnto(PoseGate::Verdict verdict, const PoseSample& sample, BodyStateObserver* observer);

}  // namespace birotor
