// Whether the rotors can still hold the vehicle in hover, decided once and
// latched (issue 34; N rotors: issue 38): a rotor known to be
// too weak stays known when FORCE later turns unusable (MODEL_MISMATCH,
// stale), so the level descent and its flare do not depend on FORCE staying
// VALID. Hover needs every rotor's hover thrust within what it can make:
// margin f_hover,i <= e_i c_T,i omega_max^2 for all i (the allocation's
// base is the exact hover f_hover, which holds the weight with the hover's
// torque, and on a fully actuated vehicle zero lateral force; on the birotor
// f_hover,i = weight / 2: 2 min_i(e_i c_T omega_max^2) >= margin x weight).
// Two ways in: the efficiencies in use (some e_i below its bound
// margin f_hover,i / (c_T,i omega_max^2) for infeasible_s), or the vehicle
// itself (the allocation limited while it sinks below its reference, the
// sink growing, for sink_detect_s: a loss so large that FORCE's
// thrust_scale sits at its plausibility floor and is refused). Then the
// descent levels first (tilt target 0) and descends once level and calm. A
// latch from the sink is undone when the rotors' commands then show that
// they hold the weight with the margin (MeasureRecovery; a payload the
// weight model does not know makes the sink a poor judge). Pure
// bookkeeping: no allocation, no throw.
#pragma once

#include <cstdint>
#include <limits>

#include "controller/controller_params.h"
#include "controller/hover_space.h"
#include "model/vehicle_description.h"

namespace birotor {

struct BodyState;
struct ReferencePoint;

inline constexpr double kNaNReport = std::numeric_limits<double>::quiet_NaN();

// What one control period saw (rotor i: entry i; entries from the rotor count on unused).
struct FeasibilityInputs {
  double efficiency[kMaxArms] = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0};  // efficiencies in use (force feedback) [1]
  bool following_force = false;                                  // they follow a usable FORCE this period
  // They carry a loss flown relative to the other rotors under a model
  // mismatch (MismatchChangeRule) since FORCE was last usable: right against
  // the others, its absolute level unknown, so no latch is taken from them
  // (the sink detection still is).
  bool relative_efficiency = false;
  // FORCE's newest thrust_scale / baseline per rotor, low-passed, including
  // samples refused below the plausibility floor (evidence, not flown) [1].
  double reported_scale[kMaxArms] = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  bool allocation_limited = false;      // the previous period's allocation was limited
  double command_rad_s[kMaxArms] = {};  // the previous period's rotor commands [rad/s]
  // Spare rotors, the cascade only: what FORCE's newest report says rotor i
  // makes when it flags it below the plausibility floor, where the
  // efficiency in use is only "at most the floor"; NaN otherwise [1]. The
  // hover check takes the lower of the two (a dead rotor is not a 20 % one).
  double below_floor_report[kMaxArms] = {kNaNReport, kNaNReport, kNaNReport, kNaNReport, kNaNReport, kNaNReport};
  double altitude_lag_m = 0.0;    // z_ref - z [m]
  double sink_behind_m_s = 0.0;   // z_dot_ref - z_dot [m/s]
  double tilt_rad = 0.0;          // phi [rad]
  double pitch_rate_rad_s = 0.0;  // phi_dot [rad/s]
  double climb_rate_m_s = 0.0;    // z_dot [m/s]
  double altitude_m = 0.0;        // z [m]
};

// The tracking entries of the inputs from the reference and the observed
// body (world frame, z up): altitude lag, sink rate behind, tilt, pitch
// rate, climb rate, height.
void SetTrackingInputs(const ReferencePoint& reference, const BodyState& body, FeasibilityInputs* in);

class HoverFeasibility {
 public:
  enum class Phase { kFeasible, kLevelling, kDescending };
  enum class Cause { kNone, kEfficiency, kSink };

  // The birotor: both rotors make max_rotor_force_n = c_T omega_max^2 [N]
  // and hover at weight_n / 2 each [N].
  HoverFeasibility(const EfficiencyParams& params, double max_rotor_force_n, double weight_n);
  // N rotors (2 .. kMaxArms): rotor i makes at most max_rotor_force_n[i] =
  // c_T,i omega_max^2 [N] at e_i = 1 and hovers at hover_force_n[i] =
  // f_hover,i > 0 [N] (SolveMultiArmHover). With spare rotors (space.
  // redundant()) hover is infeasible when no hover of the space, level or
  // tilted up to spare_hover_tilt_rad, keeps every rotor within
  // [spare_min_share, 1 / margin] x e_i c_T,i omega_max^2 instead (the
  // bounds below then only rank the rotors). A fully actuated vehicle
  // without one (space.tilts(): the trirotor) keeps the bounds and is
  // still feasible beyond them while a hover tilted up to
  // spare_hover_tilt_rad keeps every rotor within [spare_min_share,
  // LimitTiltedHoverShare's].
  HoverFeasibility(const EfficiencyParams& params, int rotor_count, const double* max_rotor_force_n,
                   const double* hover_force_n, const HoverSpace& space = HoverSpace());

  // Lets the rotors' commands undo a latch from the sink
  // (EfficiencyParams::sink_recover_s): every rotor's omega_max [rad/s] and
  // g [m/s^2]. Until called a latch holds for the flight.
  void MeasureRecovery(double omega_max_rad_s, double gravity_m_s2);

  // One control period of dt_s [s]; returns the phase after it.
  Phase Update(const FeasibilityInputs& in, double dt_s);

  Phase phase() const { return phase_; }
  bool infeasible() const { return phase_ != Phase::kFeasible; }
  Cause cause() const { return cause_; }
  // Entries into the infeasible phase detected from the vehicle's sink
  // (Cause::kSink) since construction.
  int64_t entries_by_sink() const { return entries_by_sink_; }
  // Latches from the sink undone by the rotors' measure since construction.
  int64_t recoveries() const { return recoveries_; }
  // Without a spare rotor (the trirotor's space) a tilted hover counts only
  // with every rotor within max_share (the cascade's spare_max_share: room
  // for its torque above the weak rotor; 1 / margin until called) [1].
  void LimitTiltedHoverShare(double max_share) { tilted_max_share_ = max_share; }
  // Latched: the weak rotor (0-based) and its efficiency [1]: while FORCE
  // is usable it follows the efficiency in use (at most its bound; once
  // detected from the sink only downwards), otherwise it holds.
  int weak_rotor() const { return weak_rotor_; }
  double weak_efficiency() const { return weak_efficiency_; }
  // The efficiency rotor i is flown with: the latched one for the weak
  // rotor (after a recovery too, until FORCE is usable again).
  double EfficiencyFor(int rotor, double efficiency_in_use) const;
  // The largest efficiency of rotor i at which hover is still infeasible:
  // margin f_hover,i / (c_T,i omega_max^2) [1]; the birotor's
  // margin x weight / (2 c_T omega_max^2). With spare rotors the least-norm
  // hover's: the others may take rotor i's share below it.
  double FeasibilityBound(int rotor = 0) const { return bound_[rotor]; }
  int rotor_count() const { return rotor_count_; }

 private:
  void Latch(Cause cause, int weak_rotor, double efficiency);
  // Feasible again: the latch undone, the sink detection disarmed until the
  // vehicle no longer falls behind its reference (the climb back starts
  // behind it).
  void Recover();
  // One period of the recovery window; true when a full window measured
  // that the rotors hold the weight with the margin (header of
  // EfficiencyParams::sink_recover_s).
  bool HoldMeasured(const FeasibilityInputs& in, double dt_s);
  // Whether the efficiencies hold a hover: e_weakest at least its bound, or
  // with spare rotors some hover within the shares, or fully actuated a
  // tilted one (constructor).
  bool HoverHeld(const FeasibilityInputs& in, int weakest) const;
  // Rotor i's efficiency in use, or with spare rotors or a tilt the lower
  // below_floor_report when FORCE gives one (a dead rotor reads 0, not the
  // floor), for the hover check only: the latched weak efficiency stays the
  // one in use (taking the report there too, a dead rotor 3's descent
  // touched down at 3.93 m/s instead of 0.56) [1].
  double Evidence(const FeasibilityInputs& in, int rotor) const;
  // The rotor furthest below its bound: the least e_i / bound_i (ties: the lowest index).
  int Weakest(const double (&efficiency)[kMaxArms]) const;
  // Detected from the sink: the weaker by FORCE's report when it tells the
  // rotors apart, else the one the attitude loop drives hardest relative to
  // its hover speed.
  int WeakFromSink(const FeasibilityInputs& in) const;

  EfficiencyParams params_;
  int rotor_count_;
  double bound_[kMaxArms] = {};
  double hover_speed_ratio_[kMaxArms] = {};  // sqrt(f_hover,i / f_max,i): the hover's share of omega_max [1]
  double below_bound_s_ = 0.0;               // time the efficiencies have said infeasible [s]
  double sinking_s_ = 0.0;                   // time the vehicle has sunk with the allocation limited [s]
  Phase phase_ = Phase::kFeasible;
  Cause cause_ = Cause::kNone;
  int weak_rotor_ = 0;
  double weak_efficiency_ = 1.0;
  int64_t entries_by_sink_ = 0;
  int64_t recoveries_ = 0;
  double sink_start_climb_m_s_ = 0.0;  // climb rate where the sink window began [m/s]
  bool sink_armed_ = true;             // the sink detection counts (disarmed by Recover)
  // Recovered: the weak rotor is still flown at its latched efficiency
  // until FORCE is usable again (switching it back to the fallback's
  // efficiency near 1 tilted the climb back 0.2 rad).
  bool holds_weak_ = false;
  // The recovery window: omega_max and g (0: off), its length so far [s],
  // the climb rate at its start [m/s] and each rotor's integral of
  // (omega_i / omega_max)^2 over it [s].
  double omega_max_rad_s_ = 0.0;
  double gravity_m_s2_ = 0.0;
  double hold_elapsed_s_ = -1.0;  // < 0: no window open
  double hold_start_climb_m_s_ = 0.0;
  double hold_start_altitude_m_ = 0.0;  // z where the window opened [m]
  int hold_windows_ = 0;                // windows in a row that showed the margin
  double hold_share_s_[kMaxArms] = {};
  HoverSpace space_;               // the hovers the rotors can hold (spare rotors: more than one)
  double tilted_max_share_ = 1.0;  // LimitTiltedHoverShare [1]
};

}  // namespace birotor
