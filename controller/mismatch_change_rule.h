// A rotor's change flown while the estimator cannot explain the vehicle
// (FORCE not VALID by MODEL_MISMATCH alone, MismatchedOnly): a payload, an
// untared gauge or a stiffer arm make every thrust scale mu_i wrong, and
// wrong alike, so the force-feedback map falls back to the nominal one; but a
// rotor that loses thrust still moves its own mu_i against the others', and
// the estimate flags it. This rule keeps that much (issue 36 item 5: with a
// rotor loss on a changed vehicle force feedback keeps its advantage):
//  - its own baseline mu0_i, low-passed over the unflagged mismatched
//    reports (baseline_tau_s) from the airborne test on, and settled after
//    baseline_tau_s of them; a VALID report ends the episode (Reset);
//  - the common factor: the unflagged rotors' mean mu_j / mu0_j; rotor i's
//    relative change c_i = mu_i / mu0_i / common - 1;
//  - confirmed when rotor i's fault bit has been held for mismatch_confirm_s
//    with a loss c_i below -mismatch_min_change (a gain is not flown), and
//    c_i and the common factor
//    each within mismatch_max_spread of themselves throughout (a mismatch's own errors flag the rotors by turns,
//    some 15 % apart; a motor lag the file lacks swings mu by tens of per
//    cent); then the target 1 + c_i is flown, handed over with a time
//    constant of mismatch_handover_factor x the time the fault was held (the
//    nominal loop's integrators took the change on meanwhile), until c_i is
//    back within change_threshold;
//  - distrusted until the next VALID report when the flags disagree (fault
//    bits on more than one rotor in the episode: a mismatch's own errors
//    flag the rotors by turns), a fault comes before the baselines settled
//    (they may hold it already), or a flown change wanders beyond
//    mismatch_max_spread from what was confirmed; with no unflagged rotor to
//    compare with, nothing is flown.
// For any rotor count 2 .. kMaxArms; no allocation, no throw.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "controller/airborne_by_force.h"
#include "controller/controller_params.h"
#include "controller/rotor_efficiency_estimate.h"
#include "model/vehicle_description.h"

namespace birotor {

class MismatchChangeRule {
 public:
  // weight_n: the thrust the rotors make together in hover [N].
  MismatchChangeRule(const EfficiencyParams& params, double weight_n, int rotor_count);

  // One mismatched report of the rotor count (the caller has checked
  // MismatchedOnly and the count).
  void OnMismatchedReport(const RotorEfficiencyEstimate& e);
  // A VALID report: the mismatch episode ends, the next starts afresh.
  void Reset();

  // Rotor i's confirmed change is flown now.
  bool flown(int rotor) const { return flown_[Index(rotor)]; }
  // ... at this efficiency relative to the others [1].
  double target(int rotor) const { return flown_[Index(rotor)] ? 1.0 + change_[Index(rotor)] : 1.0; }
  // ... with at least this time constant [s].
  double handover_tau_s(int rotor) const { return handover_tau_s_[Index(rotor)]; }
  bool distrusted() const { return distrusted_; }

 private:
  static size_t Index(int rotor) { return static_cast<size_t>(rotor); }
  // The common factor of the unflagged, precise rotors; false: none.
  bool CommonFactor(const RotorEfficiencyEstimate& e, const std::array<bool, kMaxArms>& precise, double* common) const;
  // One rotor's confirming run or flown change: its fault bit, c_i and the
  // common factor [1]; dt_s since the previous report [s].
  void Judge(int rotor, bool fault, double change, double common, double dt_s);

  // The smallest and largest of a value over a confirming run.
  struct Span {
    double min = 0.0;
    double max = 0.0;
    bool Within(double x, double spread) const { return std::max(max, x) - std::min(min, x) <= spread; }
    void Add(double x) {
      min = std::min(min, x);
      max = std::max(max, x);
    }
  };
  struct RunSpan {
    Span change;  // c_i [1]
    Span common;  // the common factor [1]
  };

  EfficiencyParams params_;
  double weight_n_;
  int rotor_count_;
  AirborneByForce airborne_;
  int64_t last_utime_ = -1;
  bool has_baseline_ = false;
  double settled_s_ = 0.0;  // airborne mismatched reports seen [s]
  bool distrusted_ = false;
  int32_t faulted_rotors_ = 0;                       // bit i: rotor i's fault bit seen in this episode
  std::array<double, kMaxArms> baseline_{};          // mu0_i [1]
  std::array<bool, kMaxArms> flown_{};               // rotor i's change is flown
  std::array<double, kMaxArms> change_{};            // c_i of the newest precise report [1]
  std::array<double, kMaxArms> fault_held_s_{};      // rotor i's fault bit held this long [s]
  std::array<double, kMaxArms> confirming_s_{};      // ... with a large, steady change this long [s]
  std::array<RunSpan, kMaxArms> runs_{};             // the confirming runs' spans
  std::array<double, kMaxArms> confirmed_change_{};  // c_i when confirmed [1]
  std::array<double, kMaxArms> handover_tau_s_{};    // [s]
};

}  // namespace birotor
