// One elastic arm's share of the Euler-Lagrange terms M, C, G and tau of a
// planar body with arms (derived in model/multi_arm_dynamics.h's header
// comment; the birotor's thesis eq. 3.10-3.14 are its N = 2 case). The
// birotor's ComputeDynamicsTerms and ComputeMultiArmTerms both add every arm
// through AddArmTerms: one copy of the assembly, each vehicle giving only its
// geometry at a_i = phi + b_i.
#pragma once

namespace birotor {

// Arm i at one (q, v, f), in the world frame (x right, z up).
template <typename T>
struct ArmShare {
  double tip_mass_kg = 0.0;        // m_p,i [kg]
  double length_m = 0.0;           // L_i [m]
  double gravity_m_s2 = 0.0;       // g [m/s^2]
  double stiffness_n_m_rad = 0.0;  // k_i [N m/rad]
  double damping_n_m_s_rad = 0.0;  // d_i [N m s/rad]
  double lever_m = 0.0;            // l_i = L_i w_i . n_i: the thrust's moment arm about the hinge [m]
  T jx, jz;                        // L_i w_i: the tip Jacobian's phi and b_i column [m]
  T centripetal_n;                 // C's magnitude -m_p L_i a_i_dot^2 (signed as the caller's r_i) [N]
  T rx, rz;                        // the unit vector C acts along (r_i, or the birotor's [cos a_i, sin a_i])
  T nx, nz;                        // thrust direction n_i (unit)
  T deflection_rad;                // b_i [rad]
  T deflection_rate_rad_s;         // b_i_dot [rad/s]
  T force_n;                       // f_i [N]
};

// Adds arm's share to the upper triangle of mass and to coriolis,
// gravity_spring and generalized_thrust; b is b_i's coordinate index:
//   M += m_p J_i^T J_i   (x/z: m_p I; phi and b_i columns m_p L w_i; phi/phi, phi/b_i, b_i/b_i: m_p L^2)
//   C += centripetal [r_i; 0 ..]
//   G += m_p g J_i^T [0, 1] + k_i b_i + d_i b_i_dot
//   tau += f_i [n_i; l_i; l_i]
template <typename T, typename Matrix, typename Vector>
void AddArmTerms(const ArmShare<T>& arm, int b, Matrix* mass, Vector* coriolis, Vector* gravity_spring,
                 Vector* generalized_thrust) {
  constexpr int kX = 0, kZ = 1, kPhi = 2;
  const double mp = arm.tip_mass_kg, L = arm.length_m, g = arm.gravity_m_s2;
  Matrix& M = *mass;
  M(kX, kX) += mp;
  M(kZ, kZ) += mp;
  M(kX, kPhi) += mp * arm.jx;
  M(kX, b) += mp * arm.jx;
  M(kZ, kPhi) += mp * arm.jz;
  M(kZ, b) += mp * arm.jz;
  M(kPhi, kPhi) += mp * L * L;
  M(kPhi, b) += mp * L * L;
  M(b, b) += mp * L * L;
  (*coriolis)(kX) += arm.centripetal_n * arm.rx;
  (*coriolis)(kZ) += arm.centripetal_n * arm.rz;
  (*gravity_spring)(kZ) += mp * g;
  (*gravity_spring)(kPhi) += (mp * g) * arm.jz;
  (*gravity_spring)(b) += (mp * g) * arm.jz;
  (*gravity_spring)(b) +=
      arm.stiffness_n_m_rad * arm.deflection_rad + arm.damping_n_m_s_rad * arm.deflection_rate_rad_s;
  (*generalized_thrust)(kX) += arm.nx * arm.force_n;
  (*generalized_thrust)(kZ) += arm.nz * arm.force_n;
  (*generalized_thrust)(kPhi) += arm.lever_m * arm.force_n;
  (*generalized_thrust)(b) += arm.lever_m * arm.force_n;
}

}  // namespace birotor
