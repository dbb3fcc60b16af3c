// The physics floor of a level descent the rotors cannot stop (issue 34):
// level, neither rotor may make more than the weak one can (the pitch torque
// L (f2 - f1) must average zero), so the most the two make is
// 2 s_weak c_T omega_max^2 and the vehicle of mass m = m_body + 2 m_tip sinks
// with at least a = g - 2 s_weak c_T omega_max^2 / m. From height h above
// the support at vertical speed v (either sign: a climb turns into height),
// energy gives the slowest level touchdown, v_td = sqrt(v^2 + 2 a h).
// Measured from the truth at the controller's first STATUS_DESCENDING after
// the fault. A flare (controller/rotor_allocation.h) gives up ending level
// and may land below it.
#pragma once

#include "evaluation/closed_loop.h"
#include "simulator/scenario.h"

namespace birotor {

struct DescentFloor {
  bool found = false;            // a descent after the fault, with a ground to land on
  double start_s = 0.0;          // its start, from the run's start [s]
  double height_m = 0.0;         // h: truth z above the support then [m]
  double climb_m_s = 0.0;        // v: truth z_dot then [m/s]
  double sink_accel_m_s2 = 0.0;  // a [m/s^2]
  double touchdown_m_s = 0.0;    // v_td [m/s]
};

// The weak rotor's thrust scale after every step of the scenario [1].
double WeakestFinalThrustScale(const Scenario& scenario);
// a = g - 2 s_weak c_T omega_max^2 / (m_body + 2 m_tip) of the flown vehicle [m/s^2].
double LevelSinkAccelM_S2(const Scenario& scenario);
DescentFloor LevelDescentFloor(const ClosedLoopRun& run, const Scenario& scenario);

}  // namespace birotor
