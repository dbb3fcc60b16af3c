// The thrust efficiency e_i the force-feedback rotor map uses,
// omega_i = sqrt(f_i / (e_i c_T)), from FORCE's thrust_scale mu_i, used only
// as far as it is good (issue 25):
//  - frozen at 1 until airborne (FORCE's total thrust above a share of the
//    weight for a while: no ground-phase fault flag reaches the rotors);
//  - followed only while the change is real: FORCE flags rotor i's fault
//    or the shared thrust deficit, or mu_i moved by more than
//    change_threshold from its baseline (a step; a mismatch drifts), and
//    only once the baseline has settled (baseline_tau_s airborne). Then e_i = mu_i / mu0_i (at most
//    max_change_gain: no fault makes a rotor stronger), mu0_i the
//    low-passed mu_i of the unflagged flight before (baseline_tau_s), so a
//    model mismatch (stiffness, gauge scale, mass, motor lag, noise), which
//    moves mu slowly and unflagged, is left to the nominal loop's
//    integrators instead of being applied as a disturbance;
//  - a sample whose force sigma is large is not followed (above
//    max_relative_sigma x the larger of |force_i| and the rotors' mean hover
//    thrust weight / N: a dead rotor's 0 N is certain, not infinitely
//    uncertain relative to itself);
//  - what is learned is flown too (issue 36 item 5): e_i = a_i c_i, c_i the
//    change factor above (mu_i / mu0_i while flagged, else 1) and a_i the
//    absolute factor: towards mu0_i itself (within [min, max]_absolute_
//    efficiency) with absolute_tau_s while FORCE is VALID, neither
//    MODEL_MISMATCH nor CONVERGING, force_std_i <= absolute_max_relative_sigma
//    x |force_i| and absolute_settle_s of airborne FORCE seen, and only once
//    |mu0_i - 1| has exceeded absolute_threshold and absolute_min_sigmas
//    times mu0_i's relative sigma s0_i (force_std_i / |force_i| low-passed
//    like mu0_i: an offset read while the filter still converges, its
//    sigma still wide, is not flown) until it is back within half of the
//    threshold (a matched vehicle's few per cent stay with the integrators);
//    a vehicle whose rotors make 0.85 of the map (c_T -15 %, thinner air) is
//    flown with e = 0.85 instead of being left to the integrators. mu0_i is
//    itself low-passed (baseline_tau_s), so e moves on the sum of both time
//    constants, slow against the motor and the attitude loop. Otherwise a_i
//    decays towards 1 with decay_s. absolute_tau_s 0: off (the issue 25 rule);
//  - first-order towards the target with fault_tau_s, rate limited: a
//    ringing estimate cannot drive the rotors;
//  - FORCE not VALID by MODEL_MISMATCH alone but on time (OnMismatchedForce,
//    Advance's change_usable): a rotor's loss MismatchChangeRule confirmed
//    is flown relative to the unflagged rotors (no absolute factor);
//  - when FORCE is unusable or the flag clears, the efficiency decays towards
//    1 over decay_s (no jump to the nominal map); back from a fallback longer
//    than blend_after_s it is blended in with a time constant of blend_s / 3
//    for blend_s (no jump back): the handover is bumpless both ways.
// For any rotor count 2 .. kMaxArms (issue 38): VehicleController feeds it
// the birotor's FORCE, MultiArmController the N-rotor reports
// (RotorEfficiencyEstimate, force_estimate_n_t's content: its status bits,
// rotor_fault_bits, forces and force sigmas); the airborne test compares the
// rotors' summed force with the hover thrusts' sum (the birotor's weight).
// No allocation, no throw.
#pragma once

#include <array>
#include <cstdint>

#include "controller/airborne_by_force.h"
#include "controller/controller_params.h"
#include "controller/mismatch_change_rule.h"
#include "controller/rotor_efficiency_estimate.h"
#include "model/vehicle_description.h"
#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

class EfficiencyConditioner {
 public:
  // weight_n: the thrust the rotors make together in hover [N] (airborne
  // test: the birotor's weight, the N rotors' summed hover thrusts);
  // rotor_count: 2 .. kMaxArms (a report of another count is ignored).
  EfficiencyConditioner(const EfficiencyParams& params, double weight_n, int rotor_count = kBirotorRotors);

  // One healthy report (VALID, plausible scales); one not VALID or of
  // another rotor count is ignored.
  void OnForce(const RotorEfficiencyEstimate& estimate);
  // One healthy birotor FORCE sample (the caller passes VALID ones only).
  void OnForce(const ForceEstimate& estimate);
  // One report whose VALID MODEL_MISMATCH alone withdrew (MismatchedOnly;
  // others are ignored): MismatchChangeRule, with mismatch_relative.
  void OnMismatchedForce(const RotorEfficiencyEstimate& estimate);
  void OnMismatchedForce(const ForceEstimate& estimate);
  // One control period of dt_s [s]; usable: the estimate may be flown on
  // now; change_usable: not usable, but the mismatched reports are on time
  // (a change MismatchChangeRule confirmed is flown).
  void Advance(double dt_s, bool usable, bool change_usable = false);

  // e_i = a_i c_i, the efficiency the rotor map flies [1].
  double efficiency(int rotor) const { return absolute_[Index(rotor)] * change_[Index(rotor)]; }
  // c_i: mu_i / mu0_i while the change is real, else towards 1 [1].
  double change(int rotor) const { return change_[Index(rotor)]; }
  // a_i: the trusted absolute thrust_scale mu0_i, followed slowly [1].
  double absolute(int rotor) const { return absolute_[Index(rotor)]; }
  bool airborne() const { return airborne_.airborne(); }
  // A loss relative to the others (MismatchChangeRule) has been flown since
  // the estimate was last usable: the efficiencies are right against each
  // other, their absolute level is not known.
  bool relative_since_usable() const { return relative_since_usable_; }
  // The unflagged thrust_scale mu0_i the efficiency is relative to [1].
  double baseline(int rotor) const { return baseline_[Index(rotor)]; }
  int rotor_count() const { return rotor_count_; }

 private:
  static size_t Index(int rotor) { return static_cast<size_t>(rotor); }
  // One report of the rotor count, taken (the caller has checked VALID).
  void Take(const RotorEfficiencyEstimate& estimate);
  // The absolute rule's facts of one VALID sample (trusted_, absolute_target_).
  void NoteAbsolute(const RotorEfficiencyEstimate& estimate);

  EfficiencyParams params_;
  double weight_n_;
  int rotor_count_;
  std::array<double, kMaxArms> change_;    // c_i [1]
  std::array<double, kMaxArms> absolute_;  // a_i [1]
  std::array<double, kMaxArms> absolute_target_;
  std::array<bool, kMaxArms> absolute_engaged_{};  // |mu0_i - 1| beyond absolute_threshold (hysteresis)
  std::array<bool, kMaxArms> trusted_{};           // the newest sample's mu0_i may be flown absolutely
  std::array<double, kMaxArms> target_;
  std::array<bool, kMaxArms> flagged_{};  // the estimate says rotor i's change is real
  AirborneByForce airborne_;              // the airborne test on the VALID reports
  MismatchChangeRule mismatch_;           // a rotor's change under a model mismatch
  int64_t last_utime_ = -1;
  bool has_baseline_ = false;
  bool relative_since_usable_ = false;
  bool was_following_ = false;
  double blend_left_s_ = 0.0;  // time left of the blend after a fallback [s]
  double unusable_s_ = 0.0;    // length of the current fallback [s]
  double settled_s_ = 0.0;     // airborne FORCE time seen [s]
  std::array<double, kMaxArms> baseline_;
  std::array<double, kMaxArms> baseline_relative_std_;  // s0_i: force_std_i / |force_i| low-passed like mu0_i [1]
};

}  // namespace birotor
