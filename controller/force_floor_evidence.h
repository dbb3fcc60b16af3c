// What FORCE says about a rotor below the plausibility floor (issue 34): an
// 80 % loss puts FORCE's thrust_scale at or below min_plausible_thrust_scale,
// where the controller refuses it (issue 23). Two uses that keep the refusal
// for everything else: a rotor FORCE keeps flagging as faulty with a scale
// below the floor (at_floor_samples in a row) is flown as the floor (its
// scale is at most that); and every VALID report, refused ones included, is
// low-passed as evidence for HoverFeasibility's sink detection (never flown
// by itself). No allocation, no throw.
#pragma once

#include <cstdint>

#include "controller/controller_params.h"
#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

class ForceFloorEvidence {
 public:
  // low_pass_s: time constant of the reported scales [s] (infeasible_s).
  ForceFloorEvidence(const SupervisionParams& params, double low_pass_s) : params_(params), low_pass_s_(low_pass_s) {}

  // Sets a flagged rotor's scale below the floor to the floor once it has
  // been there at_floor_samples in a row; returns how many scales it set.
  int FlyAtTheFloor(ForceEstimate* estimate);

  // One report arrived at now_us [us] (VALID, within the clock windows,
  // newer than the last): thrust_scale_i / baseline_i low-passed.
  void Note(const ForceEstimate& estimate, int64_t now_us, const double (&baseline)[kBirotorRotors]);

  // The low-passed thrust_scale / baseline of rotor i (1 before any) [1].
  double reported_scale(int rotor) const { return reported_scale_[rotor]; }

 private:
  SupervisionParams params_;
  double low_pass_s_;
  int below_floor_run_[kBirotorRotors] = {0, 0};  // flagged samples below the floor in a row, per rotor
  double reported_scale_[kBirotorRotors] = {1.0, 1.0};
  int64_t reported_utime_ = -1;  // newest noted report [us]
};

}  // namespace birotor
