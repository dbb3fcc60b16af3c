// Closed-form Euler-Lagrange dynamics of a planar body with N elastic arms
// (model/vehicle_description.h), templated on the scalar so that Ceres Jets
// give exact Jacobians. The birotor of model/birotor_dynamics.h is N = 2 with
// alpha = {pi, 0}, theta = {0, 0} (tests/model/multi_arm_dynamics_test.cc).
//
// Coordinates q = [x, z, phi, b_1 .. b_N] (n = 3 + N), v = q_dot. With
// a_i = phi + b_i and, in the world frame,
//   r_i = R(a_i) e_i = [cos(a_i + alpha_i), sin(a_i + alpha_i)]   (arm direction)
//   w_i = R(a_i) [-sin alpha_i, cos alpha_i] = d r_i / d a_i        (perpendicular)
//   n_i = R(a_i) u_i = [-sin(a_i + theta_i), cos(a_i + theta_i)]   (thrust)
// the tip is p_i = p + L_i r_i and p_i_dot = p_dot + L_i a_i_dot w_i, i.e.
// p_i_dot = J_i v with the 2 x n tip Jacobian J_i = [I_2, L_i w_i (phi column),
// L_i w_i (b_i column), 0 elsewhere].
//   T = 1/2 m |p_dot|^2 + 1/2 J phi_dot^2 + sum_i 1/2 m_p,i |J_i v|^2
//   U = m g z + sum_i m_p,i g (z + L_i r_i,z) + sum_i 1/2 k_i b_i^2
//   D = sum_i 1/2 d_i b_i_dot^2,  generalized force of f_i n_i at p_i: J_i^T n_i f_i
// The Euler-Lagrange equations d/dt dT/dv - dT/dq + dU/dq + dD/dv = tau give
//   M q_ddot + C + G = tau, with (per arm i, mp = m_p,i, L = L_i)
//   M = diag(m, m, J, 0 ..) + sum_i mp J_i^T J_i
//       (x/z rows: mp [1, 0; 0, 1], phi and b_i columns mp L w_i; phi/phi, phi/b_i,
//        b_i/b_i: mp L^2, since |w_i| = 1)
//   C = sum_i mp J_i^T J_i_dot v = -sum_i mp L a_i_dot^2 [r_i; 0 ..]
//       (J_i_dot v = -L a_i_dot^2 r_i; w_i . r_i = 0 removes it from the phi, b rows)
//   G = [0, (m + sum mp) g, sum_i mp g L w_i,z, .. mp g L w_i,z + k_i b_i + d_i b_i_dot ..]
//       (w_i,z = cos(a_i + alpha_i); hinge damping carried in G as in the birotor)
//   tau = sum_i f_i J_i^T n_i = [sum f_i n_i; sum l_i f_i; .. l_i f_i ..]
//       (w_i . n_i = cos(alpha_i - theta_i), so the lever l_i = L_i cos(alpha_i -
//        theta_i) of the description is constant).
// With alpha_i = pi, theta_i = 0: w_1 = -[-sin a, cos a] = s_1 n_1, l_1 = -L, which
// is birotor_dynamics.h's s_i L term by term.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "model/arm_terms.h"
#include "model/birotor_dynamics.h"
#include "model/vehicle_description.h"

namespace birotor {

// q = [x, z, phi, b_1 .. b_N]: the body coordinates kX, kZ, kPhi of
// birotor_dynamics.h, then one deflection per arm.
inline constexpr int kBodyCoordinates = 3;
inline constexpr int kMaxCoordinates = kBodyCoordinates + kMaxArms;
constexpr int DeflectionIndex(int arm) { return kBodyCoordinates + arm; }
inline int CoordinateCount(const VehicleDescription& vehicle) { return kBodyCoordinates + vehicle.arm_count; }

// Dynamic size with fixed maximum storage: no heap allocation at any N.
template <typename T>
using MultiCoords = Eigen::Matrix<T, Eigen::Dynamic, 1, 0, kMaxCoordinates, 1>;
template <typename T>
using MultiCoordMatrix = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCoordinates, kMaxCoordinates>;
template <typename T>
using ArmForces = Eigen::Matrix<T, Eigen::Dynamic, 1, 0, kMaxArms, 1>;

// M, C, G and tau of the header comment at one (q, v, f); sizes n = 3 + N.
template <typename T>
struct MultiArmTerms {
  MultiCoordMatrix<T> mass;           // M(q) [kg, kg m, kg m^2]
  MultiCoords<T> coriolis;            // C(q, v) [N, N m]
  MultiCoords<T> gravity_spring;      // G(q, v): gravity, hinge spring and damping [N, N m]
  MultiCoords<T> generalized_thrust;  // tau(q, f) [N, N m]
};

// Arm i's directions at a_i = phi + b_i: r_i = [cos, sin](a_i + alpha_i) (w_i
// = [-r_i,z, r_i,x]) and the thrust direction n_i = [-sin, cos](a_i + theta_i);
// with the constant lever l_i = L_i cos(alpha_i - theta_i) (ThrustLeverM).
template <typename T>
struct ArmDirections {
  T rx, rz;              // r_i (unit)
  T nx, nz;              // n_i (unit)
  double lever_m = 0.0;  // l_i [m]
};

// The directions from a_i by the library's sin and cos (the simulator's).
template <typename T>
ArmDirections<T> MultiArmDirections(const ArmDescription& arm, const T& a) {
  using std::cos;
  using std::sin;
  const T thrust_angle = a + arm.thrust_angle_rad;
  return {cos(a + arm.angle_rad), sin(a + arm.angle_rad), -sin(thrust_angle), cos(thrust_angle), arm.ThrustLeverM()};
}

// Arm i's share of the terms at (a_i_dot = phi_dot + b_i_dot, b_i, b_i_dot,
// f_i) with its directions at a_i. T may be a Jet over only the variables
// the arm depends on (the EKF's Jacobian).
template <typename T>
ArmShare<T> MultiArmShareWith(const VehicleDescription& vehicle, int i, const T& a_dot, const T& b, const T& b_dot,
                              const T& force_n, const ArmDirections<T>& directions) {
  const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
  const double mp = arm.tip_mass_kg, L = arm.length_m;
  ArmShare<T> share;
  share.tip_mass_kg = mp;
  share.length_m = L;
  share.gravity_m_s2 = vehicle.gravity_m_s2;
  share.stiffness_n_m_rad = arm.stiffness_n_m_rad;
  share.damping_n_m_s_rad = arm.damping_n_m_s_rad;
  share.lever_m = directions.lever_m;
  share.jx = -L * directions.rz;  // L_i w_i
  share.jz = L * directions.rx;
  share.centripetal_n = -mp * L * a_dot * a_dot;  // J_i_dot v = -L a_dot^2 r_i
  share.rx = directions.rx;
  share.rz = directions.rz;
  share.nx = directions.nx;
  share.nz = directions.nz;
  share.deflection_rad = b;
  share.deflection_rate_rad_s = b_dot;
  share.force_n = force_n;
  return share;
}

// Arm i's share of the terms at (phi, phi_dot, b_i, b_i_dot, f_i): its
// geometry at a_i = phi + b_i (r_i, w_i, n_i of the header comment).
template <typename T>
ArmShare<T> MultiArmShare(const VehicleDescription& vehicle, int i, const T& phi, const T& phi_dot, const T& b,
                          const T& b_dot, const T& force_n) {
  const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
  return MultiArmShareWith<T>(vehicle, i, phi_dot + b_dot, b, b_dot, force_n, MultiArmDirections<T>(arm, phi + b));
}

// M, C, G and tau: the body's own terms, then add_arm(i, &terms) for every
// arm in order (it adds arm i's share, AddArmTerms), then M's lower triangle
// from its upper one.
template <typename T, typename AddArm>
MultiArmTerms<T> AssembleMultiArmTerms(const VehicleDescription& vehicle, AddArm&& add_arm) {
  const int n = CoordinateCount(vehicle);
  MultiArmTerms<T> out;
  out.mass.setZero(n, n);
  out.mass(kX, kX) = T(vehicle.body_mass_kg);
  out.mass(kZ, kZ) = T(vehicle.body_mass_kg);
  out.mass(kPhi, kPhi) = T(vehicle.body_inertia_kg_m2);
  out.coriolis.setZero(n);
  out.gravity_spring.setZero(n);
  out.gravity_spring(kZ) = T(vehicle.body_mass_kg * vehicle.gravity_m_s2);
  out.generalized_thrust.setZero(n);
  for (int i = 0; i < vehicle.arm_count; ++i) add_arm(i, &out);
  for (int r = 0; r < n; ++r)
    for (int col = r + 1; col < n; ++col) out.mass(col, r) = out.mass(r, col);
  return out;
}

template <typename T>
MultiArmTerms<T> ComputeMultiArmTerms(const VehicleDescription& vehicle, const MultiCoords<T>& q,
                                      const MultiCoords<T>& v, const ArmForces<T>& force_n) {
  return AssembleMultiArmTerms<T>(vehicle, [&](int i, MultiArmTerms<T>* out) {
    const int b = DeflectionIndex(i);
    const ArmShare<T> share = MultiArmShare<T>(vehicle, i, q(kPhi), v(kPhi), q(b), v(b), force_n(i));
    AddArmTerms(share, b, &out->mass, &out->coriolis, &out->gravity_spring, &out->generalized_thrust);
  });
}

// Solves M x = rhs for a symmetric positive definite M by M = L D L^T (unit
// lower-triangular L, no pivoting, no square roots), in fixed maximum storage.
// Not Eigen's LLT/LDLT: their triangular solves skip right-hand-side entries
// that compare equal to zero, and a Jet compares by its value only, so at an
// equilibrium (q_ddot = 0) they drop the derivative parts and return wrong
// Jacobians.
template <typename T>
MultiCoords<T> SolveMultiArmMassMatrix(const MultiCoordMatrix<T>& mass, const MultiCoords<T>& rhs) {
  const int n = static_cast<int>(mass.rows());
  MultiCoordMatrix<T> lower = MultiCoordMatrix<T>::Zero(n, n);
  MultiCoords<T> diagonal(n), x(n);
  for (int j = 0; j < n; ++j) {
    diagonal(j) = mass(j, j);
    for (int k = 0; k < j; ++k) diagonal(j) -= lower(j, k) * lower(j, k) * diagonal(k);
    for (int i = j + 1; i < n; ++i) {
      T sum = mass(i, j);
      for (int k = 0; k < j; ++k) sum -= lower(i, k) * lower(j, k) * diagonal(k);
      lower(i, j) = sum / diagonal(j);
    }
  }
  for (int i = 0; i < n; ++i) {  // L y = rhs (y kept in x)
    x(i) = rhs(i);
    for (int k = 0; k < i; ++k) x(i) -= lower(i, k) * x(k);
  }
  for (int i = n - 1; i >= 0; --i) {  // D L^T x = y
    x(i) /= diagonal(i);
    for (int k = i + 1; k < n; ++k) x(i) -= lower(k, i) * x(k);
  }
  return x;
}

// q_ddot = M^-1 (tau - C - G).
template <typename T>
MultiCoords<T> MultiArmAcceleration(const VehicleDescription& vehicle, const MultiCoords<T>& q, const MultiCoords<T>& v,
                                    const ArmForces<T>& force_n) {
  const MultiArmTerms<T> terms = ComputeMultiArmTerms<T>(vehicle, q, v, force_n);
  return SolveMultiArmMassMatrix<T>(terms.mass,
                                    MultiCoords<T>(terms.generalized_thrust - terms.coriolis - terms.gravity_spring));
}

// Mechanical energy T + U [J]; with d_i = 0 and no thrust it is conserved.
template <typename T>
T MultiArmEnergy(const VehicleDescription& vehicle, const MultiCoords<T>& q, const MultiCoords<T>& v) {
  using std::sin;
  const ArmForces<T> no_thrust = ArmForces<T>::Zero(vehicle.arm_count);
  const MultiArmTerms<T> terms = ComputeMultiArmTerms<T>(vehicle, q, v, no_thrust);
  const double g = vehicle.gravity_m_s2;
  T energy = T(0.5) * v.dot(terms.mass * v) + vehicle.body_mass_kg * g * q(kZ);
  for (int i = 0; i < vehicle.arm_count; ++i) {
    const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
    const T b = q(DeflectionIndex(i));
    const T tip_z = q(kZ) + arm.length_m * sin(q(kPhi) + b + arm.angle_rad);
    energy += arm.tip_mass_kg * g * tip_z + 0.5 * arm.stiffness_n_m_rad * b * b;
  }
  return energy;
}

}  // namespace birotor
