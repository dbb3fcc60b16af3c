// What FORCE says about a rotor below the plausibility floor (issue 34; N
// rotors: issue 38), for any rotor count (2 .. kMaxArms): an 80 % loss puts
// FORCE's thrust_scale at or below min_plausible_thrust_scale, where the
// controller refuses it (issue 23). Two uses that keep the refusal for
// everything else: a rotor FORCE keeps flagging as faulty with a scale below
// the floor (at_floor_samples in a row) is flown as the floor (its scale is
// at most that); every VALID report, refused ones included, is
// low-passed as evidence for HoverFeasibility's sink detection (never flown
// by itself); and the newest flagged report below the floor is kept for
// the spare-rotor hover check (below_floor_report) and retirement
// (below_floor_mean). VehicleController (the birotor's FORCE, converted by
// RotorEfficiencyReportOf) and MultiArmController use it. No allocation, no
// throw.
#pragma once

#include <array>
#include <cstdint>

#include "controller/controller_params.h"
#include "controller/rotor_efficiency_estimate.h"
#include "model/vehicle_description.h"
#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

class ForceFloorEvidence {
 public:
  // low_pass_s: time constant of the reported scales [s] (infeasible_s);
  // rotor_count: the vehicle's, 2 .. kMaxArms (a report of another count is
  // no evidence).
  ForceFloorEvidence(const SupervisionParams& params, double low_pass_s, int rotor_count);

  // Sets a flagged rotor's scale below the floor to the floor once it has
  // been there at_floor_samples reports in a row; returns how many scales it
  // set. A report of another rotor count sets none and ends every run.
  int FlyAtTheFloor(RotorEfficiencyEstimate* estimate);
  // The birotor's FORCE (RotorEfficiencyReportOf), its scales set in place.
  int FlyAtTheFloor(ForceEstimate* estimate);

  // One report arrived at now_us [us]; taken when VALID, of the rotor count,
  // within the clock windows (clock_past_window_s, clock_future_window_s)
  // and newer than the last taken: thrust_scale_i / baseline_i low-passed
  // (each rotor whose scale is finite and in [0, max_plausible_thrust_scale]).
  void Note(const RotorEfficiencyEstimate& estimate, int64_t now_us, const std::array<double, kMaxArms>& baseline);
  // The birotor's FORCE with the EfficiencyConditioner's baselines [1].
  void Note(const ForceEstimate& estimate, int64_t now_us, const double (&baseline)[kBirotorRotors]);

  // The low-passed thrust_scale / baseline of rotor i (1 before any) [1].
  double reported_scale(int rotor) const { return reported_scale_[static_cast<size_t>(rotor)]; }
  int rotor_count() const { return rotor_count_; }
  // The newest report's thrust_scale of rotor i when FORCE flags it below
  // the floor (negative read as 0): what it makes, not only "at most the
  // floor"; NaN when the newest report does not [1].
  double below_floor_report(int rotor) const { return below_floor_report_[static_cast<size_t>(rotor)]; }
  // The mean thrust_scale of rotor i over its current run of flagged
  // reports below the floor (negatives as they are), once the run is
  // at_floor_samples long; NaN otherwise [1]. A dead rotor's reads about 0
  // (MultiArmController retires a spare rotor below spare_retire_scale).
  double below_floor_mean(int rotor) const;

 private:
  SupervisionParams params_;
  double low_pass_s_;
  int rotor_count_;
  std::array<int, kMaxArms> below_floor_run_{};      // flagged reports below the floor in a row, per rotor
  std::array<double, kMaxArms> reported_scale_;      // [1]
  std::array<double, kMaxArms> below_floor_report_;  // below_floor_report [1]
  std::array<int, kMaxArms> flagged_low_run_{};      // flagged reports below the floor in a row, negatives included
  std::array<double, kMaxArms> flagged_low_sum_{};   // their thrust_scale summed [1]
  int64_t reported_utime_ = -1;                      // newest noted report [us]
};

}  // namespace birotor
