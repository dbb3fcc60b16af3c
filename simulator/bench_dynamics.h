// Plant derivative with the body clamped on a test stand (scenario `bench`):
// x, z, phi and their rates are held at 0; only the arm deflections b1, b2
// and the rotor speeds evolve. Same 12-entry state as model/plant.h.
#pragma once

#include "model/plant.h"

namespace birotor {

// Arm rows from SupportedArmAcceleration (model/birotor_dynamics.h).
inline PlantState ClampedBodyDerivative(const VehicleParams& p, const PlantState& x, const PlantInput& u) {
  const double f1 = RotorThrust(p, x(kPlantOmega1), u.thrust_scale[0]);
  const double f2 = RotorThrust(p, x(kPlantOmega2), u.thrust_scale[1]);
  const Eigen::Vector2d b_ddot = SupportedArmAcceleration<double>(p, x(kPlantQ + kB1), x(kPlantQ + kB2),
                                                                  x(kPlantV + kB1), x(kPlantV + kB2), f1, f2);
  PlantState x_dot = PlantState::Zero();
  x_dot(kPlantQ + kB1) = x(kPlantV + kB1);
  x_dot(kPlantQ + kB2) = x(kPlantV + kB2);
  x_dot(kPlantV + kB1) = b_ddot(0);
  x_dot(kPlantV + kB2) = b_ddot(1);
  x_dot(kPlantOmega1) = (ClampCommand(p, u.omega_cmd_rad_s[0]) - x(kPlantOmega1)) / p.motor_time_constant_s;
  x_dot(kPlantOmega2) = (ClampCommand(p, u.omega_cmd_rad_s[1]) - x(kPlantOmega2)) / p.motor_time_constant_s;
  return x_dot;
}

}  // namespace birotor
