// Plant derivative with the body clamped on a test stand (scenario `bench`):
// x, z, phi and their rates are held at 0; only the arm deflections b1, b2
// and the rotor speeds evolve. Same 12-entry state as model/plant.h.
#pragma once

#include "model/plant.h"

namespace birotor {

// b rows of M q_ddot + C + G = tau with q_body = v_body = 0 (thesis eq. 3.10):
// M_bb = m_p L^2 on the diagonal (no b1-b2 coupling) and C_b = 0, so
//   b_i_ddot = (tau_b_i - G_b_i) / (m_p L^2).
inline PlantState ClampedBodyDerivative(const VehicleParams& p, const PlantState& x, const PlantInput& u) {
  Coords<double> q = Coords<double>::Zero();
  Coords<double> v = Coords<double>::Zero();
  q(kB1) = x(kPlantQ + kB1);
  q(kB2) = x(kPlantQ + kB2);
  v(kB1) = x(kPlantV + kB1);
  v(kB2) = x(kPlantV + kB2);
  const double f1 = RotorThrust(p, x(kPlantOmega1), u.thrust_scale[0]);
  const double f2 = RotorThrust(p, x(kPlantOmega2), u.thrust_scale[1]);
  const DynamicsTerms<double> terms = ComputeDynamicsTerms<double>(p, q, v, f1, f2);
  const Coords<double> rhs = terms.generalized_thrust - terms.coriolis - terms.gravity_spring;
  PlantState x_dot = PlantState::Zero();
  x_dot(kPlantQ + kB1) = v(kB1);
  x_dot(kPlantQ + kB2) = v(kB2);
  x_dot(kPlantV + kB1) = rhs(kB1) / terms.mass(kB1, kB1);
  x_dot(kPlantV + kB2) = rhs(kB2) / terms.mass(kB2, kB2);
  x_dot(kPlantOmega1) = (ClampCommand(p, u.omega_cmd_rad_s[0]) - x(kPlantOmega1)) / p.motor_time_constant_s;
  x_dot(kPlantOmega2) = (ClampCommand(p, u.omega_cmd_rad_s[1]) - x(kPlantOmega2)) / p.motor_time_constant_s;
  return x_dot;
}

}  // namespace birotor
