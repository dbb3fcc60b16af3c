// Static equilibrium of the birotor: the deflections and rotor thrusts that
// hold the body still at a given tilt (thesis section 3.3.3).
#pragma once

#include "model/birotor_dynamics.h"
#include "samples/rotor_count.h"

namespace birotor {

struct Equilibrium {
  double deflection_rad[kBirotorRotors] = {0, 0};  // b1, b2 [rad]
  double force_n[kBirotorRotors] = {0, 0};         // f1, f2 [N]
  double omega_rad_s[kBirotorRotors] = {0, 0};     // rotor speeds with mu = 1 [rad/s]
  double residual = 0;                             // max |M q_ddot| left by the solver
  bool converged = false;
};

// Hover equilibrium at tilt phi = 0 (the only tilt at which the planar
// birotor can hover): solves tau(q, f) = G(q) for (b1, b2, f1, f2) by Newton's
// method on the z, phi, b1 and b2 rows, starting from the small-angle
// solution b_i = s_i (m_p g L - L f) / k.
Equilibrium SolveHoverEquilibrium(const BirotorParams& p);

}  // namespace birotor
