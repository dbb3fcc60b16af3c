// From the law's total thrust and thrust difference to the two rotors within
// what they can make, keeping attitude before altitude (issue 25): the
// difference f2 - f1 (the pitch torque, tau = L (f2 - f1), eq. 3.12) is kept
// and the total moved into the range both rotors can still make; only when
// the difference alone is beyond reach is it clipped too. And the flare of a
// descent the rotors cannot hover (FlareForces). Pure.
#pragma once

#include "samples/rotor_count.h"

namespace birotor {

struct RotorAllocation {
  double force_n[kBirotorRotors] = {0.0, 0.0};  // rotor 1, 2 [N], each within [0, max_force_n[i]]
  bool total_limited = false;                   // the total was moved (altitude gives way)
  bool difference_limited = false;              // the difference was clipped (attitude gives way)
};

// f1 = (F - D) / 2, f2 = (F + D) / 2 with 0 <= f_i <= max_force_n[i]:
// D clipped to [-2 max1, 2 max2] first, then F to [|D|, min(2 max1 + D, 2 max2 - D)].
RotorAllocation AllocateAttitudeFirst(double total_force_n, double force_difference_n,
                                      const double (&max_force_n)[kBirotorRotors]);

// The vehicle near the ground in a descent it cannot stop (world frame).
struct FlareState {
  double height_m = 0.0;          // above the ground [m]
  double sink_rate_m_s = 0.0;     // -z_dot [m/s]
  double tilt_rad = 0.0;          // phi [rad]
  double pitch_rate_rad_s = 0.0;  // phi_dot [rad/s]
};

struct BodyState;

// The flare's state of the observed body above ground_z_m, the take-off
// level (the first POSE's z) [m].
FlareState FlareStateOf(const BodyState& body, double ground_z_m);
// Whether a descent the rotors cannot stop flares now: a tilt budget at
// all, sinking faster than descent_rate_m_s [m/s], above the take-off
// level and lower than sink rate x flare_time_s [s]; on the ground (no
// sink) it ends by itself.
bool InFlareWindow(const FlareState& state, double tilt_budget_rad, double descent_rate_m_s, double flare_time_s);

struct FlareLimits {
  double tilt_budget_rad = 0.0;                     // |phi| allowed at touchdown [rad]
  double min_time_to_go_s = 0.0;                    // t_go is not taken below this (the motor lag) [s]
  double pitch_inertia_kg_m2 = 0.0;                 // J_eff = J + 2 m_p L^2
  double arm_length_m = 0.0;                        // L
  double max_force_n[kBirotorRotors] = {0.0, 0.0};  // what each rotor can make now [N]
};

// The flare: level, both rotors make at most twice the weak rotor's maximum
// (a sink the law cannot stop); the strong rotor may make an extra dF above
// the weak one until touchdown, decelerating the sink by dF t_go / m at the
// cost of a pitch acceleration L dF / J_eff towards the weak side. dF is the
// constant one that brings the tilt in that direction, s phi, to the budget
// exactly at touchdown, t_go = height / sink rate (at least min_time_to_go_s):
//   s phi + s phi_dot t_go + L dF t_go^2 / (2 J_eff) = budget
//   dF = 2 J_eff (budget - s phi - s phi_dot t_go) / (L t_go^2), within [0, max_strong - max_weak],
// with s = +1 when rotor 2 is the strong one (phi'' = L (f2 - f1) / J_eff)
// and -1 when rotor 1 is. Re-solved every period on the measured state, so
// the rotor's lag is made up for by the next periods. The weak rotor stays
// at its maximum: F = 2 max_weak + dF, D = s dF (for AllocateAttitudeFirst).
struct FlareForces {
  double total_force_n = 0.0;       // F [N]
  double force_difference_n = 0.0;  // D = f2 - f1 [N]
  double extra_force_n = 0.0;       // dF [N]
  double time_to_go_s = 0.0;        // t_go [s]
};
FlareForces FlareForcesFor(const FlareState& state, const FlareLimits& limits);

}  // namespace birotor
