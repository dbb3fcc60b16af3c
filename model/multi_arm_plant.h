// The plant of any VehicleDescription as a first-order system for
// integration: mechanical state [q, v] of model/multi_arm_dynamics.h plus one
// rotor speed per arm, driven by rotor speed commands and the thrust-scale
// factors mu_i. The N-arm counterpart of model/plant.h, built from the same
// pieces (MotorLagRate, RotorThrust, Rk4Step), so the birotor description
// gives the birotor plant (tests/model/multi_arm_plant_test.cc).
//   q_dot = v,  v_dot = M^-1 (tau - C - G)                  (multi_arm_dynamics.h)
//   omega_i_dot = (clamp(omega_cmd_i, 0, omega_max) - omega_i) / tau_m,i
//   f_i = mu_i c_T,i omega_i^2
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>

#include "model/multi_arm_dynamics.h"
#include "model/multi_arm_linearization.h"
#include "model/plant.h"
#include "model/rk4.h"

namespace birotor {

// State x = [q (n), v (n), omega_1 .. omega_N], n = 3 + N: 2 n + N entries,
// at most 2 kMaxCoordinates + kMaxArms, in fixed maximum storage.
inline constexpr int kMaxMultiArmPlantStateSize = 2 * kMaxCoordinates + kMaxArms;
using MultiArmPlantState = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxMultiArmPlantStateSize, 1>;

// Named blocks of the state for a description (n = CoordinateCount).
inline int MultiArmPlantSize(const VehicleDescription& vehicle) {
  return 2 * CoordinateCount(vehicle) + vehicle.arm_count;
}
inline int MultiArmQIndex(const VehicleDescription& /*vehicle*/, int coordinate) { return coordinate; }
inline int MultiArmVIndex(const VehicleDescription& vehicle, int coordinate) {
  return CoordinateCount(vehicle) + coordinate;
}
inline int MultiArmOmegaIndex(const VehicleDescription& vehicle, int arm) { return 2 * CoordinateCount(vehicle) + arm; }

// Inputs held constant over one integration step; entries [0, N) are used.
struct MultiArmPlantInput {
  std::array<double, kMaxArms> omega_cmd_rad_s{};               // rotor speed commands (clamped inside) [rad/s]
  std::array<double, kMaxArms> thrust_scale{1, 1, 1, 1, 1, 1};  // mu_i = s_i (1 + eta_i) [1]
};

// f_i = mu_i c_T,i omega_i^2 [N] of every rotor in the state x.
inline ArmForces<double> MultiArmThrusts(const VehicleDescription& vehicle, const MultiArmPlantState& x,
                                         const MultiArmPlantInput& u) {
  ArmForces<double> force_n(vehicle.arm_count);
  for (int i = 0; i < vehicle.arm_count; ++i) {
    force_n(i) = RotorThrust(vehicle.arms[static_cast<size_t>(i)].thrust_coeff_n_s2_rad2,
                             x(MultiArmOmegaIndex(vehicle, i)), u.thrust_scale[static_cast<size_t>(i)]);
  }
  return force_n;
}

// The plant at rest in hover at the origin: SolveMultiArmHover's deflections,
// omega_i = sqrt(f_i / c_T,i) (mu = 1), every position, tilt and rate zero.
inline MultiArmPlantState MultiArmHoverPlantState(const VehicleDescription& vehicle, const MultiArmHover& hover) {
  MultiArmPlantState x = MultiArmPlantState::Zero(MultiArmPlantSize(vehicle));
  for (int i = 0; i < vehicle.arm_count; ++i) {
    x(MultiArmQIndex(vehicle, DeflectionIndex(i))) = hover.deflection_rad(i);
    const double force_n = std::max(hover.force_n(i), 0.0);
    x(MultiArmOmegaIndex(vehicle, i)) =
        std::sqrt(force_n / vehicle.arms[static_cast<size_t>(i)].thrust_coeff_n_s2_rad2);
  }
  return x;
}

// Time derivative of the plant state.
inline MultiArmPlantState MultiArmPlantDerivative(const VehicleDescription& vehicle, const MultiArmPlantState& x,
                                                  const MultiArmPlantInput& u) {
  const int n = CoordinateCount(vehicle);
  const MultiCoords<double> q = x.segment(0, n);
  const MultiCoords<double> v = x.segment(n, n);
  MultiArmPlantState x_dot(MultiArmPlantSize(vehicle));
  x_dot.segment(0, n) = v;
  x_dot.segment(n, n) = MultiArmAcceleration<double>(vehicle, q, v, MultiArmThrusts(vehicle, x, u));
  for (int i = 0; i < vehicle.arm_count; ++i) {
    const int w = MultiArmOmegaIndex(vehicle, i);
    x_dot(w) = MotorLagRate(vehicle.omega_max_rad_s, vehicle.arms[static_cast<size_t>(i)].motor_time_constant_s, x(w),
                            u.omega_cmd_rad_s[static_cast<size_t>(i)]);
  }
  return x_dot;
}

// Time derivative of the plant state on a support that holds the body still
// and level (the bench's clamp, or the ground under a landed vehicle; the
// N-arm counterpart of model/bench_dynamics.h): x, z, phi and their rates
// do not change, and each arm obeys its own row of M q_ddot = tau - C - G
// with the body's accelerations zero, M_bb = m_p,i L_i^2, C_b = 0:
//   m_p L^2 b_ddot + d b_dot + k b + m_p g L cos(phi + b + alpha) = l f.
inline MultiArmPlantState MultiArmSupportedDerivative(const VehicleDescription& vehicle, const MultiArmPlantState& x,
                                                      const MultiArmPlantInput& u) {
  const int n = CoordinateCount(vehicle);
  const MultiCoords<double> q = x.segment(0, n);
  const MultiCoords<double> v = x.segment(n, n);
  const MultiArmTerms<double> terms = ComputeMultiArmTerms<double>(vehicle, q, v, MultiArmThrusts(vehicle, x, u));
  MultiArmPlantState x_dot = MultiArmPlantState::Zero(MultiArmPlantSize(vehicle));
  for (int i = 0; i < vehicle.arm_count; ++i) {
    const int b = DeflectionIndex(i);
    x_dot(b) = v(b);
    x_dot(n + b) = (terms.generalized_thrust(b) - terms.coriolis(b) - terms.gravity_spring(b)) / terms.mass(b, b);
    const int w = MultiArmOmegaIndex(vehicle, i);
    x_dot(w) = MotorLagRate(vehicle.omega_max_rad_s, vehicle.arms[static_cast<size_t>(i)].motor_time_constant_s, x(w),
                            u.omega_cmd_rad_s[static_cast<size_t>(i)]);
  }
  return x_dot;
}

// Deflection b_i [rad] at rest of arm i on a level supported body under the
// thrust force_n [N]: the root of the supported row above with b_dot = 0,
//   k b + m_p g L cos(b + alpha) = l f,
// by Newton from the small-angle b = (l f - m_p g L cos alpha) / k (the
// birotor's StaticDeflectionRad); 4 iterations leave < 1e-15 rad.
inline double MultiArmStaticDeflectionRad(const VehicleDescription& vehicle, int arm, double force_n) {
  const ArmDescription& a = vehicle.arms[static_cast<size_t>(arm)];
  const double weight_moment = a.tip_mass_kg * vehicle.gravity_m_s2 * a.length_m;  // m_p g L [N m]
  const double thrust_moment = a.ThrustLeverM() * force_n;                         // l f [N m]
  double b = (thrust_moment - weight_moment * std::cos(a.angle_rad)) / a.stiffness_n_m_rad;
  for (int k = 0; k < 4; ++k) {
    const double residual = a.stiffness_n_m_rad * b + weight_moment * std::cos(b + a.angle_rad) - thrust_moment;
    b -= residual / (a.stiffness_n_m_rad - weight_moment * std::sin(b + a.angle_rad));
  }
  return b;
}

// One RK4 step of the plant over dt_s [s] with u held.
inline MultiArmPlantState StepMultiArmPlant(const VehicleDescription& vehicle, const MultiArmPlantState& x,
                                            const MultiArmPlantInput& u, double dt_s) {
  return Rk4Step(x, dt_s, [&](const MultiArmPlantState& s) { return MultiArmPlantDerivative(vehicle, s, u); });
}

}  // namespace birotor
