// The arm dynamics of model/birotor_dynamics.h reduced to what the arms need,
// with stiffness k and damping d as template scalars so that Ceres Jets
// differentiate through them (identification): the arm of a body clamped on
// the bench or held on the ground (the simulator's bench scenario,
// identification's bench fit, the EKF on the ground) and
// the arms of the free-flying vehicle (the EKF's process model,
// identification's flight fit). Tests check both against the full model.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "model/birotor_dynamics.h"
#include "model/birotor_params.h"
#include "model/vehicle_description.h"

namespace birotor {

// Clamped body (bench), arm i with sign s_i (s_1 = -1, s_2 = +1): the b row of
// thesis eq. 3.10 with x, z, phi held,
//   m_p L^2 b_ddot + d b_dot + k b + s_i m_p g L cos(b) = s_i L f_i.
// Returns b_ddot [rad/s^2]. Uses L, g of `known`; k, d and the tip mass m_p
// [kg] are parameters (identification fits all three on the bench).
template <typename T>
T ClampedArmAcceleration(const BirotorParams& known, int arm, const T& k, const T& d, const T& tip_mass_kg, const T& b,
                         const T& b_dot, const T& force_n) {
  using std::cos;
  const double s = kArmSign[arm];
  const double L = known.arm_length_m, g = known.gravity_m_s2;
  return (s * L * force_n - s * tip_mass_kg * g * L * cos(b) - k * b - d * b_dot) / (tip_mass_kg * L * L);
}

// The hinge of one clamped arm of any vehicle (model/vehicle_description.h):
// length L, thrust lever l = L cos(alpha - theta) [m] and the direction
// alpha through its cosine and sine (stored, not the angle, so that the
// birotor's alpha = pi gives cos = -1, sin = 0 exactly).
struct ClampedArmGeometry {
  double length_m = 0.25;      // L [m]
  double lever_m = 0.25;       // l [m]
  double cos_angle = 1.0;      // cos alpha [1]
  double sin_angle = 0.0;      // sin alpha [1]
  double gravity_m_s2 = 9.81;  // g [m/s^2]
};

// Arm i of the birotor: alpha = pi (arm 1) or 0 (arm 2), l = s_i L.
inline ClampedArmGeometry BirotorClampedArm(const BirotorParams& known, int arm) {
  return {known.arm_length_m, kArmSign[arm] * known.arm_length_m, kArmSign[arm], 0.0, known.gravity_m_s2};
}

// Arm i of a vehicle description: L_i, l_i = L_i cos(alpha_i - theta_i), alpha_i.
inline ClampedArmGeometry ClampedArmOf(const VehicleDescription& vehicle, int arm) {
  const ArmDescription& a = vehicle.arms[static_cast<size_t>(arm)];
  return {a.length_m, a.ThrustLeverM(), std::cos(a.angle_rad), std::sin(a.angle_rad), vehicle.gravity_m_s2};
}

// Clamped body, one arm of any planar vehicle: the supported row of
// model/multi_arm_plant.h (MultiArmSupportedDerivative) at phi = 0,
//   m_p L^2 b_ddot + d b_dot + k b + m_p g L cos(b + alpha) = l f,
// with cos(b + alpha) = cos b cos alpha - sin b sin alpha; the birotor's
// row above is alpha = pi or 0. Returns b_ddot [rad/s^2].
template <typename T>
T ClampedArmAcceleration(const ClampedArmGeometry& arm, const T& k, const T& d, const T& tip_mass_kg, const T& b,
                         const T& b_dot, const T& force_n) {
  using std::cos;
  using std::sin;
  const double L = arm.length_m;
  const T gravity_cos = cos(b) * arm.cos_angle - sin(b) * arm.sin_angle;
  return (arm.lever_m * force_n - tip_mass_kg * arm.gravity_m_s2 * L * gravity_cos - k * b - d * b_dot) /
         (tip_mass_kg * L * L);
}

// The same with m_p of `known`.
template <typename T>
T ClampedArmAcceleration(const BirotorParams& known, int arm, const T& k, const T& d, const T& b, const T& b_dot,
                         const T& force_n) {
  return ClampedArmAcceleration<T>(known, arm, k, d, T(known.tip_mass_kg), b, b_dot, force_n);
}

// Arm accelerations (b1_ddot, b2_ddot) of a body held still and level by a
// support (a test stand, or the ground under a landed vehicle), with the
// vehicle's own k and d: the clamped-arm row above for each arm (M_bb =
// m_p L^2, no b1-b2 coupling, C_b = 0 with the body still) [rad/s^2].
template <typename T>
Eigen::Matrix<T, 2, 1> SupportedArmAcceleration(const BirotorParams& p, const T& b1, const T& b2, const T& b1_dot,
                                                const T& b2_dot, const T& force1_n, const T& force2_n) {
  const T k(p.arm_stiffness_n_m_rad), d(p.arm_damping_n_m_s_rad);
  return Eigen::Matrix<T, 2, 1>(ClampedArmAcceleration(p, 0, k, d, b1, b1_dot, force1_n),
                                ClampedArmAcceleration(p, 1, k, d, b2, b2_dot, force2_n));
}

// State of the free-flight arm model. For a free body in uniform gravity the
// arm and pitch-rate dynamics do not depend on x, z, phi nor on the body
// velocity, so this is the whole state they need.
enum FreeArmIndex : int {
  kFreePhiDot = 0,  // body pitch rate [rad/s]
  kFreeB1 = 1,      // deflection of arm 1 [rad]
  kFreeB2 = 2,      // deflection of arm 2 [rad]
  kFreeB1Dot = 3,   // [rad/s]
  kFreeB2Dot = 4,   // [rad/s]
};
constexpr int kFreeArmStateSize = 5;
template <typename T>
using FreeArmState = Eigen::Matrix<T, kFreeArmStateSize, 1>;

// Derivative of the free-flight arm state and the specific force at the body
// centre in body axes [m/s^2] (what the accelerometer measures). Evaluates
// M q_ddot = tau - C - G of thesis eq. 3.14 (same terms as
// model/birotor_dynamics.h ComputeDynamicsTerms) at q = (0, 0, 0, b1, b2),
// v = (0, 0, phi_dot, b1_dot, b2_dot) with gravity removed: with phi = 0 the
// world axes are the body axes, and uniform gravity only adds -g to every z
// acceleration, so (x_ddot, z_ddot) with g = 0 is the specific force.
//
// The translational block of M is (m + 2 m_p) I, so x, z are eliminated by
// the Schur complement: with M = [M_t I, B; B^T, D] (B: 2x3, D: 3x3 over
// phi, b1, b2) and rhs [r_t; r_r],
//   (D - B^T B / M_t) w = r_r - B^T r_t / M_t,   w = (phi_ddot, b1_ddot, b2_ddot),
//   u = (x_ddot, z_ddot) = (r_t - B w) / M_t,
// a 3x3 SPD system solved by LDL^T in closed form (this runs per RK4 stage on
// Jets, so it is written out entry by entry). k and d enter the b rows of G:
// G_b = k b + d b_dot.
// The tip mass m_p [kg] is a parameter too (flight identification fits it).
template <typename T>
FreeArmState<T> FreeArmDerivative(const BirotorParams& known, const T& k, const T& d, const T& tip_mass_kg,
                                  const FreeArmState<T>& x, const T& force1_n, const T& force2_n,
                                  Eigen::Matrix<T, 2, 1>* specific_force_m_s2 = nullptr) {
  using std::cos;
  using std::sin;
  const T& mp = tip_mass_kg;
  const double L = known.arm_length_m;
  const T mt = known.body_mass_kg + 2.0 * mp;  // translational mass M_t [kg]
  const T mp_l2 = mp * L * L;                  // [kg m^2]
  const double s1L = kArmSign[0] * L, s2L = kArmSign[1] * L;
  const T& b1 = x(kFreeB1);
  const T& b2 = x(kFreeB2);
  const T c1 = cos(b1), sn1 = sin(b1), c2 = cos(b2), sn2 = sin(b2);
  // Tip Jacobian entries d p_i / d a_i = s_i L n_i = s_i L [-sin b_i, cos b_i] [m].
  const T jx1 = -s1L * sn1, jz1 = s1L * c1, jx2 = -s2L * sn2, jz2 = s2L * c2;
  // B = m_p [jx1 + jx2, jx1, jx2; jz1 + jz2, jz1, jz2] [kg m].
  const T bx0 = mp * (jx1 + jx2), bx1 = mp * jx1, bx2 = mp * jx2;
  const T bz0 = mp * (jz1 + jz2), bz1 = mp * jz1, bz2 = mp * jz2;
  // Right-hand side tau - C - G (g = 0): thrust f_i n_i, centripetal
  // -m_p s_i L a_dot_i^2 r_i on x, z; torques s_i L f_i; hinge k b + d b_dot.
  const T a1_dot = x(kFreePhiDot) + x(kFreeB1Dot), a2_dot = x(kFreePhiDot) + x(kFreeB2Dot);
  const T cen1 = mp * s1L * a1_dot * a1_dot, cen2 = mp * s2L * a2_dot * a2_dot;
  const T rx = -sn1 * force1_n - sn2 * force2_n + cen1 * c1 + cen2 * c2;
  const T rz = c1 * force1_n + c2 * force2_n + cen1 * sn1 + cen2 * sn2;
  const T t1 = s1L * force1_n, t2 = s2L * force2_n;
  const T r_phi = t1 + t2;
  const T r_b1 = t1 - k * b1 - d * x(kFreeB1Dot);
  const T r_b2 = t2 - k * b2 - d * x(kFreeB2Dot);
  // Reduced system S w = y, S = D - B^T B / M_t (symmetric), y = r_r - B^T r_t / M_t.
  const T inv_mt = 1.0 / mt;
  const T s00 = (known.body_inertia_kg_m2 + 2.0 * mp_l2) - (bx0 * bx0 + bz0 * bz0) * inv_mt;
  const T s01 = mp_l2 - (bx0 * bx1 + bz0 * bz1) * inv_mt;
  const T s02 = mp_l2 - (bx0 * bx2 + bz0 * bz2) * inv_mt;
  const T s11 = mp_l2 - (bx1 * bx1 + bz1 * bz1) * inv_mt;
  const T s12 = -(bx1 * bx2 + bz1 * bz2) * inv_mt;
  const T s22 = mp_l2 - (bx2 * bx2 + bz2 * bz2) * inv_mt;
  const T y0 = r_phi - (bx0 * rx + bz0 * rz) * inv_mt;
  const T y1 = r_b1 - (bx1 * rx + bz1 * rz) * inv_mt;
  const T y2 = r_b2 - (bx2 * rx + bz2 * rz) * inv_mt;
  // LDL^T: S = L D L^T with unit lower L.
  const T d0 = s00;
  const T l10 = s01 / d0, l20 = s02 / d0;
  const T d1 = s11 - l10 * s01;
  const T l21 = (s12 - l20 * s01) / d1;
  const T d2 = s22 - l20 * s02 - l21 * l21 * d1;
  const T z1 = y1 - l10 * y0;
  const T z2 = y2 - l20 * y0 - l21 * z1;
  const T b2_ddot = z2 / d2;
  const T b1_ddot = z1 / d1 - l21 * b2_ddot;
  const T phi_ddot = y0 / d0 - l10 * b1_ddot - l20 * b2_ddot;
  FreeArmState<T> x_dot;
  x_dot(kFreePhiDot) = phi_ddot;
  x_dot(kFreeB1) = x(kFreeB1Dot);
  x_dot(kFreeB2) = x(kFreeB2Dot);
  x_dot(kFreeB1Dot) = b1_ddot;
  x_dot(kFreeB2Dot) = b2_ddot;
  if (specific_force_m_s2 != nullptr) {
    (*specific_force_m_s2)(0) = (rx - bx0 * phi_ddot - bx1 * b1_ddot - bx2 * b2_ddot) * inv_mt;
    (*specific_force_m_s2)(1) = (rz - bz0 * phi_ddot - bz1 * b1_ddot - bz2 * b2_ddot) * inv_mt;
  }
  return x_dot;
}

// The same with m_p of `known` (the EKF's process model).
template <typename T>
FreeArmState<T> FreeArmDerivative(const BirotorParams& known, const T& k, const T& d, const FreeArmState<T>& x,
                                  const T& force1_n, const T& force2_n,
                                  Eigen::Matrix<T, 2, 1>* specific_force_m_s2 = nullptr) {
  return FreeArmDerivative<T>(known, k, d, T(known.tip_mass_kg), x, force1_n, force2_n, specific_force_m_s2);
}

}  // namespace birotor
