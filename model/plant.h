// The birotor plant as a first-order system for integration: mechanical
// state [q, v] plus the two rotor speeds, driven by rotor speed commands and
// the thrust-scale factors mu_i (efficiency times turbulence).
//   q_dot = v,  v_dot = M^-1 (tau - C - G)          (thesis eq. 3.14)
//   omega_i_dot = (clamp(omega_cmd_i, 0, omega_max) - omega_i) / tau_m
//   f_i = mu_i c_T omega_i^2
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "model/birotor_dynamics.h"
#include "model/equilibrium.h"
#include "model/rk4.h"
#include "samples/rotor_count.h"

namespace birotor {

// Named blocks of the plant state vector.
enum PlantIndex : int {
  kPlantQ = 0,        // q = [x, z, phi, b1, b2]: 5 entries
  kPlantV = 5,        // v = q_dot: 5 entries
  kPlantOmega1 = 10,  // rotor 1 speed [rad/s]
  kPlantOmega2 = 11,  // rotor 2 speed [rad/s]
};
constexpr int kPlantStateSize = 12;
using PlantState = Eigen::Matrix<double, kPlantStateSize, 1>;

// Inputs held constant over one integration step.
struct PlantInput {
  double omega_cmd_rad_s[kBirotorRotors] = {0, 0};  // rotor speed commands (clamped inside)
  double thrust_scale[kBirotorRotors] = {1, 1};     // mu_i = s_i (1 + eta_i) [1]
};

inline double ClampCommand(double omega_max_rad_s, double omega_cmd_rad_s) {
  return std::clamp(omega_cmd_rad_s, 0.0, omega_max_rad_s);
}
inline double ClampCommand(const BirotorParams& p, double omega_cmd_rad_s) {
  return ClampCommand(p.omega_max_rad_s, omega_cmd_rad_s);
}

// The first-order rotor speed lag (shared/spec/reference-vehicle.md), the one
// copy used by the plant, the clamped bench plant and the EKF's process model:
//   omega_dot = (clamp(omega_cmd) - omega) / tau_m   [rad/s^2]
// Its exact zero-order-hold step is MotorStep below; d(omega_dot)/d(omega) =
// -1 / tau_m.
// The scalar form serves any rotor of a VehicleDescription (model/multi_arm_plant.h).
inline double MotorLagRate(double omega_max_rad_s, double tau_m_s, double omega_rad_s, double omega_cmd_rad_s) {
  return (ClampCommand(omega_max_rad_s, omega_cmd_rad_s) - omega_rad_s) / tau_m_s;
}
inline double MotorLagRate(const BirotorParams& p, double omega_rad_s, double omega_cmd_rad_s) {
  return MotorLagRate(p.omega_max_rad_s, p.motor_time_constant_s, omega_rad_s, omega_cmd_rad_s);
}

// Rotor thrust f = mu c_T omega^2 [N] (scalar form: any rotor of a description).
inline double RotorThrust(double thrust_coeff_n_s2_rad2, double omega_rad_s, double thrust_scale) {
  return thrust_scale * thrust_coeff_n_s2_rad2 * omega_rad_s * omega_rad_s;
}
inline double RotorThrust(const BirotorParams& p, double omega_rad_s, double thrust_scale) {
  return RotorThrust(p.thrust_coeff_n_s2_rad2, omega_rad_s, thrust_scale);
}

// The plant at rest in hover at the origin: the equilibrium's deflections and
// rotor speeds, every position, tilt and rate zero (a fixed point of
// PlantDerivative with the equilibrium's speeds as commands).
inline PlantState HoverPlantState(const Equilibrium& eq) {
  PlantState x = PlantState::Zero();
  x(kPlantQ + kB1) = eq.deflection_rad[0];
  x(kPlantQ + kB2) = eq.deflection_rad[1];
  x(kPlantOmega1) = eq.omega_rad_s[0];
  x(kPlantOmega2) = eq.omega_rad_s[1];
  return x;
}

// Time derivative of the plant state.
inline PlantState PlantDerivative(const BirotorParams& p, const PlantState& x, const PlantInput& u) {
  const Coords<double> q = x.segment<kNumCoordinates>(kPlantQ);
  const Coords<double> v = x.segment<kNumCoordinates>(kPlantV);
  const double f1 = RotorThrust(p, x(kPlantOmega1), u.thrust_scale[0]);
  const double f2 = RotorThrust(p, x(kPlantOmega2), u.thrust_scale[1]);
  PlantState x_dot;
  x_dot.segment<kNumCoordinates>(kPlantQ) = v;
  x_dot.segment<kNumCoordinates>(kPlantV) = GeneralizedAcceleration<double>(p, q, v, f1, f2);
  x_dot(kPlantOmega1) = MotorLagRate(p, x(kPlantOmega1), u.omega_cmd_rad_s[0]);
  x_dot(kPlantOmega2) = MotorLagRate(p, x(kPlantOmega2), u.omega_cmd_rad_s[1]);
  return x_dot;
}

// Exact zero-order-hold step of the first-order motor model
//   omega_dot = (omega_cmd - omega) / tau_m
// over dt_s with the (clamped) command held: omega+ = c + (omega - c) exp(-dt / tau_m).
template <typename T>
T MotorStep(const T& omega_rad_s, double omega_cmd_rad_s, const T& tau_m_s, double dt_s) {
  using std::exp;
  return omega_cmd_rad_s + (omega_rad_s - omega_cmd_rad_s) * exp(-dt_s / tau_m_s);
}

// One RK4 step of the plant over dt_s [s] with u held.
inline PlantState StepPlant(const BirotorParams& p, const PlantState& x, const PlantInput& u, double dt_s) {
  return Rk4Step(x, dt_s, [&](const PlantState& s) { return PlantDerivative(p, s, u); });
}

}  // namespace birotor
