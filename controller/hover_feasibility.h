// Whether the rotors can still hold the vehicle in hover, decided once and
// latched for the flight (issue 34): a rotor known to be too weak stays
// known when FORCE later turns unusable (MODEL_MISMATCH, stale), so the
// level descent and its flare do not depend on FORCE staying VALID. Two ways
// in: the efficiencies in use (2 min_i(e_i c_T omega_max^2) below
// feasibility_margin x weight for infeasible_s), or the vehicle itself (the
// allocation limited while it sinks below its reference for sink_detect_s:
// a loss so large that FORCE's thrust_scale sits at its plausibility floor
// and is refused). Then the descent levels first (tilt target 0) and
// descends once level and calm. Pure bookkeeping: no allocation, no throw.
#pragma once

#include "controller/controller_params.h"
#include "samples/rotor_count.h"

namespace birotor {

// What one control period saw.
struct FeasibilityInputs {
  double efficiency[kBirotorRotors] = {1.0, 1.0};  // efficiencies in use (force feedback) [1]
  bool following_force = false;                    // they follow a usable FORCE this period
  // FORCE's newest thrust_scale / baseline per rotor, low-passed, including
  // samples refused below the plausibility floor (evidence, not flown) [1].
  double reported_scale[kBirotorRotors] = {1.0, 1.0};
  bool allocation_limited = false;                    // the previous period's allocation was limited
  double command_rad_s[kBirotorRotors] = {0.0, 0.0};  // the previous period's rotor commands [rad/s]
  double altitude_lag_m = 0.0;                        // z_ref - z [m]
  double sink_behind_m_s = 0.0;                       // z_dot_ref - z_dot [m/s]
  double tilt_rad = 0.0;                              // phi [rad]
  double pitch_rate_rad_s = 0.0;                      // phi_dot [rad/s]
};

class HoverFeasibility {
 public:
  enum class Phase { kFeasible, kLevelling, kDescending };
  enum class Cause { kNone, kEfficiency, kSink };

  // max_rotor_force_n: c_T omega_max^2 [N]; weight_n [N].
  HoverFeasibility(const EfficiencyParams& params, double max_rotor_force_n, double weight_n);

  // One control period of dt_s [s]; returns the phase after it.
  Phase Update(const FeasibilityInputs& in, double dt_s);

  Phase phase() const { return phase_; }
  bool infeasible() const { return phase_ != Phase::kFeasible; }
  Cause cause() const { return cause_; }
  // Latched: the weak rotor (0 or 1) and its efficiency [1]: while FORCE
  // is usable it follows the efficiency in use (at most the bound; once
  // detected from the sink only downwards), otherwise it holds.
  int weak_rotor() const { return weak_rotor_; }
  double weak_efficiency() const { return weak_efficiency_; }
  // The efficiency rotor i is flown with: the latched one for the weak rotor.
  double EfficiencyFor(int rotor, double efficiency_in_use) const;
  // The largest efficiency of the weaker rotor at which hover is still
  // infeasible: margin x weight / (2 c_T omega_max^2) [1].
  double FeasibilityBound() const { return bound_; }

 private:
  void Latch(Cause cause, int weak_rotor, double efficiency);

  EfficiencyParams params_;
  double bound_;
  double below_bound_s_ = 0.0;  // time the efficiencies have said infeasible [s]
  double sinking_s_ = 0.0;      // time the vehicle has sunk with the allocation limited [s]
  Phase phase_ = Phase::kFeasible;
  Cause cause_ = Cause::kNone;
  int weak_rotor_ = 0;
  double weak_efficiency_ = 1.0;
};

}  // namespace birotor
