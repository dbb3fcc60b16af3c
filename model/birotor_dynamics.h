// Closed-form Euler-Lagrange dynamics of the planar birotor with elastic arms
// (thesis eq. 3.10-3.14, reference-vehicle.md "Physical model"), templated on
// the scalar type so that Ceres Jets give exact Jacobians.
//
// Coordinates q = [x, z, phi, b1, b2], velocities v = q_dot. World frame: x
// right, z up. Arm i points along s_i * body x with s_1 = -1, s_2 = +1, so
//   p_i = p + s_i L r_i,   r_i = [cos a_i, sin a_i],   a_i = phi + b_i,
//   n_i = [-sin a_i, cos a_i]   (thrust direction, perpendicular to the arm),
//   p_i_dot = p_dot + s_i L a_i_dot n_i.
// With the tip Jacobian J_i = d p_i_dot / d v (2x5):
//   M = diag(m, m, J, 0, 0) + m_p sum_i J_i^T J_i
//   C = m_p sum_i J_i^T J_i_dot v = -m_p sum_i s_i L a_i_dot^2 [r_i; 0; 0; 0]
//       (centripetal; n_i . r_i = 0 removes it from the phi and b rows)
//   G = [0, (m + 2 m_p) g, ...] + m_p g sum_i J_i^T [0, 1] + [0, 0, 0, k b1, k b2]
//       + damping [0, 0, 0, d b1_dot, d b2_dot]
//   tau = sum_i f_i J_i^T n_i = [sum f_i n_i ; sum s_i L f_i ; s_1 L f_1 ; s_2 L f_2]
// so that M q_ddot + C + G = tau. G matches thesis eq. 3.12 row by row.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "model/arm_terms.h"
#include "model/birotor_params.h"
#include "samples/rotor_count.h"

namespace birotor {

// Named indices of the generalized coordinates q (and of v = q_dot).
enum Coordinate : int { kX = 0, kZ = 1, kPhi = 2, kB1 = 3, kB2 = 4 };
constexpr int kNumCoordinates = 5;
// Arm direction along body x: arm 1 along -x, arm 2 along +x.
constexpr double kArmSign[kBirotorRotors] = {-1.0, 1.0};

template <typename T>
using Coords = Eigen::Matrix<T, kNumCoordinates, 1>;
template <typename T>
using CoordMatrix = Eigen::Matrix<T, kNumCoordinates, kNumCoordinates>;

// Mass matrix, Coriolis/centripetal vector, gravity+spring+damping vector and
// generalized thrust of thesis eq. 3.10, evaluated at one (q, v, f).
template <typename T>
struct DynamicsTerms {
  CoordMatrix<T> mass;           // M(q) [kg, kg m, kg m^2]
  Coords<T> coriolis;            // C(q, v) [N, N m]
  Coords<T> gravity_spring;      // G(q) plus hinge damping d b_i_dot [N, N m]
  Coords<T> generalized_thrust;  // tau(q, f) [N, N m]
};

// Whether M(row, col) depends on the state: only the entries that couple a
// body translation (x, z) with a rotation (phi, b_i) do, through the tip
// Jacobian's s_i L n_i columns; every other entry is a constant mass or m_p L^2.
constexpr bool MassEntryVaries(int row, int col) { return (row <= kZ) != (col <= kZ); }

template <typename T>
DynamicsTerms<T> ComputeDynamicsTerms(const BirotorParams& p, const Coords<T>& q, const Coords<T>& v, const T& force1_n,
                                      const T& force2_n) {
  using std::cos;
  using std::sin;
  const double m = p.body_mass_kg, mp = p.tip_mass_kg, L = p.arm_length_m, g = p.gravity_m_s2;
  const T forces[kBirotorRotors] = {force1_n, force2_n};

  DynamicsTerms<T> out;
  out.mass.setZero();
  out.mass(kX, kX) = T(m);
  out.mass(kZ, kZ) = T(m);
  out.mass(kPhi, kPhi) = T(p.body_inertia_kg_m2);
  out.coriolis.setZero();
  out.gravity_spring.setZero();
  out.gravity_spring(kZ) = T(m * g);
  out.generalized_thrust.setZero();

  for (int i = 0; i < kBirotorRotors; ++i) {
    const int b = (i == 0) ? kB1 : kB2;
    const T a = q(kPhi) + q(b);
    const T a_dot = v(kPhi) + v(b);
    const T c = cos(a), s = sin(a);
    const double sL = kArmSign[i] * L;
    // Arm i along s_i body x: the tip Jacobian's phi and b_i columns are
    // s_i L n_i = s_i L [-sin a, cos a]; J_i_dot v = -s_i L a_dot^2 [cos a,
    // sin a]; the thrust's lever about the hinge is s_i L.
    ArmShare<T> arm;
    arm.tip_mass_kg = mp;
    arm.length_m = L;
    arm.gravity_m_s2 = g;
    arm.stiffness_n_m_rad = p.arm_stiffness_n_m_rad;
    arm.damping_n_m_s_rad = p.arm_damping_n_m_s_rad;
    arm.lever_m = sL;
    arm.jx = -sL * s;
    arm.jz = sL * c;
    arm.centripetal_n = -mp * sL * a_dot * a_dot;
    arm.rx = c;
    arm.rz = s;
    arm.nx = -s;
    arm.nz = c;
    arm.deflection_rad = q(b);
    arm.deflection_rate_rad_s = v(b);
    arm.force_n = forces[i];
    AddArmTerms(arm, b, &out.mass, &out.coriolis, &out.gravity_spring, &out.generalized_thrust);
  }
  // Symmetric lower triangle.
  for (int r = 0; r < kNumCoordinates; ++r)
    for (int col = r + 1; col < kNumCoordinates; ++col) out.mass(col, r) = out.mass(r, col);
  return out;
}

// Solves M x = rhs for the symmetric positive definite mass matrix by
// M = L D L^T with unit lower-triangular L, unrolled for the fixed 5x5 size
// (no square roots; several times faster than Eigen's generic LLT here, which
// took ~40 % of the simulation time).
template <typename T>
Coords<T> SolveMassMatrix(const CoordMatrix<T>& M, const Coords<T>& rhs) {
  constexpr int n = kNumCoordinates;
  T lower[n][n] = {};
  T diagonal[n];
  for (int j = 0; j < n; ++j) {
    T d = M(j, j);
    for (int k = 0; k < j; ++k) d -= lower[j][k] * lower[j][k] * diagonal[k];
    diagonal[j] = d;
    for (int i = j + 1; i < n; ++i) {
      T s = M(i, j);
      for (int k = 0; k < j; ++k) s -= lower[i][k] * lower[j][k] * diagonal[k];
      lower[i][j] = s / d;
    }
  }
  T y[n];
  for (int i = 0; i < n; ++i) {
    T s = rhs(i);
    for (int k = 0; k < i; ++k) s -= lower[i][k] * y[k];
    y[i] = s;
  }
  Coords<T> x;
  for (int i = n - 1; i >= 0; --i) {
    T s = y[i] / diagonal[i];
    for (int k = i + 1; k < n; ++k) s -= lower[k][i] * x(k);
    x(i) = s;
  }
  return x;
}

// Generalized acceleration q_ddot = M^-1 (tau - C - G) (thesis eq. 3.14).
template <typename T>
Coords<T> GeneralizedAcceleration(const BirotorParams& p, const Coords<T>& q, const Coords<T>& v, const T& force1_n,
                                  const T& force2_n) {
  const DynamicsTerms<T> terms = ComputeDynamicsTerms(p, q, v, force1_n, force2_n);
  return SolveMassMatrix<T>(terms.mass, terms.generalized_thrust - terms.coriolis - terms.gravity_spring);
}

// Static deflection of arm i on a held level body under its own tip weight
// and thrust force_n: k b_i = s_i L (f_i - m_p g), s_i = kArmSign (small angle,
// cos b ~ 1 to 2e-6 relative). With the motors stopped b1 = +m_p g L / k and
// b2 = -m_p g L / k (+-2.69e-4 rad for the reference vehicle).
inline double StaticDeflectionRad(const BirotorParams& p, int arm, double force_n) {
  return kArmSign[arm] * p.arm_length_m * (force_n - p.tip_mass_kg * p.gravity_m_s2) / p.arm_stiffness_n_m_rad;
}

// Mechanical energy T + U [J] (kinetic, gravitational and elastic), used to
// check the integrator: with d = 0 and no thrust it is conserved.
template <typename T>
T MechanicalEnergy(const BirotorParams& p, const Coords<T>& q, const Coords<T>& v) {
  const T zero(0.0);
  const DynamicsTerms<T> terms = ComputeDynamicsTerms(p, q, v, zero, zero);
  T energy = T(0.5) * v.dot(terms.mass * v) + p.body_mass_kg * p.gravity_m_s2 * q(kZ);
  for (int i = 0; i < kBirotorRotors; ++i) {
    const int b = (i == 0) ? kB1 : kB2;
    using std::sin;
    const T tip_z = q(kZ) + kArmSign[i] * p.arm_length_m * sin(q(kPhi) + q(b));
    energy += p.tip_mass_kg * p.gravity_m_s2 * tip_z + 0.5 * p.arm_stiffness_n_m_rad * q(b) * q(b);
  }
  return energy;
}

// Position of rotor i's hub in the world frame [m].
template <typename T>
Eigen::Matrix<T, 2, 1> TipPosition(const BirotorParams& p, const Coords<T>& q, int rotor) {
  using std::cos;
  using std::sin;
  const T a = q(kPhi) + q(rotor == 0 ? kB1 : kB2);
  const double sL = kArmSign[rotor] * p.arm_length_m;
  return Eigen::Matrix<T, 2, 1>(q(kX) + sL * cos(a), q(kZ) + sL * sin(a));
}

}  // namespace birotor
