// The physics floor of a level descent for N rotors (issue 38, the
// birotor's evaluation/descent_floor.h generalised). Level with the hover's
// torque balance (and, fully actuated, no lateral force), the thrusts are
// lambda f_hover: the hover scaled, the only direction of the square
// allocation (N = 2 on F_z and torque, the trirotor on all three rows) and
// the base the N allocation keeps (controller/wrench_allocation.h). The most
// of it rotor i makes is s_i c_T,i omega_max^2, so
//   lambda = min_i s_i c_T,i omega_max^2 / f_hover,i,   a = g (1 - lambda)
// (the birotor: f_hover = m g / 2, a = g - 2 s c_T omega_max^2 / m). From
// height h above the take-off level at vertical speed v (a climb turns into
// height) the slowest level touchdown is v_td = sqrt(v^2 + 2 a h). The
// N-rotor loop has no ground contact: the touchdown is the truth's first
// crossing of the take-off level (the scenario's start z) after the
// descent's start, its speed -z_dot there.
#pragma once

#include <array>

#include "evaluation/multi_arm_closed_loop.h"
#include "model/multi_arm_linearization.h"
#include "model/vehicle_description.h"
#include "simulator/scenario.h"

namespace birotor {

// Without a descent (the nominal map: no efficiency, no infeasibility)
// h, v and the touchdown are taken from the fault on, found false.
struct MultiArmDescent {
  bool found = false;            // a descent after the fault, above the take-off level
  double start_s = 0.0;          // its start (or the fault's), from the run's start [s]
  double height_m = 0.0;         // h: truth z above the take-off level then [m]
  double climb_m_s = 0.0;        // v: truth z_dot then [m/s]
  double sink_accel_m_s2 = 0.0;  // a [m/s^2]
  double floor_m_s = 0.0;        // v_td of a level descent [m/s]
  double touchdown_m_s = 0.0;    // the flown touchdown speed [m/s]; NaN: the run ended above the level
  double peak_tilt_rad = 0.0;    // max |phi| from the fault to the touchdown (or the end) [rad]
};

// Each rotor's thrust scale after every step of the scenario [1].
std::array<double, kMaxArms> FinalThrustScales(const Scenario& scenario);
// a = g (1 - lambda) above [m/s^2] (0 when lambda >= 1: the hover is feasible).
double MultiArmLevelSinkAccelM_S2(const VehicleDescription& vehicle, const MultiArmHover& hover,
                                  const std::array<double, kMaxArms>& scale);
MultiArmDescent MultiArmDescentOf(const MultiArmClosedLoopRun& run, const VehicleDescription& vehicle,
                                  const Scenario& scenario);

}  // namespace birotor
