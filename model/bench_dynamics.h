// Plant derivative with the body clamped on a test stand (scenario `bench`):
// x, z, phi and their rates are held at 0; only the arm deflections b1, b2
// and the rotor speeds evolve. Same 12-entry state as model/plant.h, used by
// the simulator's bench scenarios.
#pragma once

#include "model/arm_dynamics.h"
#include "model/plant.h"
#include "samples/rotor_count.h"

namespace birotor {

// b_i_ddot from the clamped-arm row of thesis eq. 3.10 (model/arm_dynamics.h)
// with the vehicle's k and d; omega_i_dot from the first-order motor model.
inline PlantState ClampedBodyDerivative(const BirotorParams& p, const PlantState& x, const PlantInput& u) {
  PlantState x_dot = PlantState::Zero();
  const double forces_n[kBirotorRotors] = {RotorThrust(p, x(kPlantOmega1), u.thrust_scale[0]),
                                           RotorThrust(p, x(kPlantOmega2), u.thrust_scale[1])};
  for (int arm = 0; arm < kBirotorRotors; ++arm) {
    const int b = arm == 0 ? kB1 : kB2;
    x_dot(kPlantQ + b) = x(kPlantV + b);
    x_dot(kPlantV + b) = ClampedArmAcceleration<double>(p, arm, p.arm_stiffness_n_m_rad, p.arm_damping_n_m_s_rad,
                                                        x(kPlantQ + b), x(kPlantV + b), forces_n[arm]);
  }
  x_dot(kPlantOmega1) = MotorLagRate(p, x(kPlantOmega1), u.omega_cmd_rad_s[0]);
  x_dot(kPlantOmega2) = MotorLagRate(p, x(kPlantOmega2), u.omega_cmd_rad_s[1]);
  return x_dot;
}

}  // namespace birotor
