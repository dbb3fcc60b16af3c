// Arm dynamics with the identified parameters (stiffness k, damping d) as
// template scalars, so Ceres Jets differentiate through them: the arm of a
// body clamped on the bench, and the arms of the free-flying vehicle.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "estimator/birotor_dynamics.h"
#include "estimator/vehicle_params.h"

namespace birotor {

// Clamped body (bench), arm i with sign s_i (s_1 = -1, s_2 = +1): the b row of
// thesis eq. 3.10 with x, z, phi held,
//   m_p L^2 b_ddot + d b_dot + k b + s_i m_p g L cos(b) = s_i L f_i.
// Returns b_ddot [rad/s^2]. Uses m_p, L, g of `known`; k, d are parameters.
template <typename T>
T ClampedArmAcceleration(const VehicleParams& known, int arm, const T& k, const T& d, const T& b,
                         const T& b_dot, const T& force_n) {
  using std::cos;
  const double s = kArmSign[arm];
  const double mp = known.tip_mass_kg, L = known.arm_length_m, g = known.gravity_m_s2;
  return (s * L * force_n - s * mp * g * L * cos(b) - k * b - d * b_dot) / (mp * L * L);
}

// State of the free-flight arm model. For a free body in uniform gravity the
// arm and pitch-rate dynamics do not depend on x, z, phi nor on the body
// velocity, so this is the whole state they need.
enum FreeArmIndex : int {
  kFreePhiDot = 0,   // body pitch rate [rad/s]
  kFreeB1 = 1,       // deflection of arm 1 [rad]
  kFreeB2 = 2,       // deflection of arm 2 [rad]
  kFreeB1Dot = 3,    // [rad/s]
  kFreeB2Dot = 4,    // [rad/s]
};
constexpr int kFreeArmStateSize = 5;
template <typename T>
using FreeArmState = Eigen::Matrix<T, kFreeArmStateSize, 1>;

// Derivative of the free-flight arm state and the specific force at the body
// centre in body axes [m/s^2] (what the accelerometer measures). Evaluates
// q_ddot = M^-1 (tau - C - G) of thesis eq. 3.14 (estimator/birotor_dynamics.h)
// at q = (0, 0, 0, b1, b2), v = (0, 0, phi_dot, b1_dot, b2_dot) with gravity
// removed: with phi = 0 the world axes are the body axes, and uniform gravity
// only adds -g to every z acceleration, so (x_ddot, z_ddot) with g = 0 is the
// specific force. k and d enter G linearly: G_b += k b + d b_dot.
template <typename T>
FreeArmState<T> FreeArmDerivative(const VehicleParams& known, const T& k, const T& d,
                                  const FreeArmState<T>& x, const T& force1_n, const T& force2_n,
                                  Eigen::Matrix<T, 2, 1>* specific_force_m_s2 = nullptr) {
  VehicleParams p = known;
  p.arm_stiffness_n_m_rad = 0.0;
  p.arm_damping_n_m_s_rad = 0.0;
  p.gravity_m_s2 = 0.0;
  Coords<T> q = Coords<T>::Zero();
  Coords<T> v = Coords<T>::Zero();
  q(kB1) = x(kFreeB1);
  q(kB2) = x(kFreeB2);
  v(kPhi) = x(kFreePhiDot);
  v(kB1) = x(kFreeB1Dot);
  v(kB2) = x(kFreeB2Dot);
  DynamicsTerms<T> terms = ComputeDynamicsTerms<T>(p, q, v, force1_n, force2_n);
  terms.gravity_spring(kB1) += k * q(kB1) + d * v(kB1);
  terms.gravity_spring(kB2) += k * q(kB2) + d * v(kB2);
  const Coords<T> rhs = terms.generalized_thrust - terms.coriolis - terms.gravity_spring;
  const Coords<T> acc = terms.mass.llt().solve(rhs);
  FreeArmState<T> x_dot;
  x_dot(kFreePhiDot) = acc(kPhi);
  x_dot(kFreeB1) = x(kFreeB1Dot);
  x_dot(kFreeB2) = x(kFreeB2Dot);
  x_dot(kFreeB1Dot) = acc(kB1);
  x_dot(kFreeB2Dot) = acc(kB2);
  if (specific_force_m_s2 != nullptr) *specific_force_m_s2 = Eigen::Matrix<T, 2, 1>(acc(kX), acc(kZ));
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

}  // namespace birotor
