// The flare of the infeasible descent for any VehicleDescription: the
// birotor's FlareForcesFor (controller/rotor_allocation.h) for N rotors.
// Near the ground, in a descent the rotors cannot stop, the thrusts that
// make the most world-vertical force while the pitch torque tilts the body
// towards the vehicle's strong side by at most the flare's tilt budget at
// touchdown. Pure, fixed size, no allocation. docs/controller.md, "Flare
// with N rotors".
#pragma once

#include "controller/controller_params.h"
#include "controller/rotor_allocation.h"
#include "model/vehicle_description.h"

namespace birotor {

// The vehicle's geometry and what its rotors can make now.
struct MultiArmFlareLimits {
  double tilt_budget_rad = 0.0;      // |phi| allowed at touchdown [rad]
  double min_time_to_go_s = 0.0;     // t_go is not taken below this (the slowest motor's lag) [s]
  double pitch_inertia_kg_m2 = 0.0;  // J_eff = J + sum m_p,i L_i^2 [kg m^2]
  int rotor_count = 0;               // N, 2 .. kMaxArms
  bool holds_lateral = false;        // fully actuated: the body F_x row is held at 0
  // Column i of WrenchAllocation: body F_x, F_z [N] and pitch torque [N m] per N of thrust f_i.
  double lateral[kMaxArms] = {};
  double vertical[kMaxArms] = {};
  double torque_m[kMaxArms] = {};
  double max_force_n[kMaxArms] = {};  // u_i = e_i c_T,i omega_max^2, what rotor i can make now [N]
};

// The geometry of the limits from the description (every max_force_n 0);
// holds_lateral when MultiArmControlModeFor is kFullyActuated.
MultiArmFlareLimits FlareGeometryOf(const VehicleDescription& vehicle, double tilt_budget_rad);

// The tilt budget the vehicle's flare takes: flare_tilt_fully_actuated_rad on
// a fully actuated vehicle, else flare_tilt_rad [rad].
double FlareTiltBudgetFor(const VehicleDescription& vehicle, const EfficiencyParams& params);

// The flare's thrusts: with s the sign of the torque every rotor makes at
// its maximum (the strong side; +1 when that is 0), t_go = height / sink
// rate (at least min_time_to_go_s) and the torque that brings s phi to the
// budget exactly at touchdown,
//   s phi + s phi_dot t_go + tau_want t_go^2 / (2 J_eff) = budget,
// the f in [0, u] that maximise the world vertical force
//   sum_i f_i (sin(phi) W_x,i + cos(phi) W_z,i)
// with 0 <= s W_tau f <= max(tau_want, 0) and, on a fully actuated
// vehicle, W_x f = 0: its thrust along the body's z as the birotor's, so
// the tilt is the flare's only lateral cost (free, the trirotor with rotor
// 1 at 30 % put 14 N sideways for 1 N more vertical force). A linear
// programme with at most two rows, solved exactly on its vertices (every
// thrust at 0 or u_i but at most one per active row, which meets it).
// Re-solved every period on the measured state. On the birotor (W_z = 1,
// W_tau = -+L) it is FlareForcesFor: the weak rotor at its maximum, the
// strong one dF above.
struct MultiArmFlareForces {
  double force_n[kMaxArms] = {};  // f_i [N]
  double torque_n_m = 0.0;        // W_tau f [N m]
  double vertical_n = 0.0;        // the world vertical force they make at phi [N]
  double time_to_go_s = 0.0;      // t_go [s]
};
MultiArmFlareForces MultiArmFlareForcesFor(const FlareState& state, const MultiArmFlareLimits& limits);

}  // namespace birotor
