#include "model/equilibrium.h"

#include <ceres/jet.h>

#include <Eigen/LU>
#include <cmath>

#include "samples/rotor_count.h"

namespace birotor {
namespace {

using Jet4 = ceres::Jet<double, 4>;

// Static balance rows z, phi, b1, b2 of tau - G with v = 0; unknowns
// [b1, b2, f1, f2].
template <typename T>
Eigen::Matrix<T, 4, 1> StaticResidual(const BirotorParams& p, const Eigen::Matrix<T, 4, 1>& unknowns) {
  Coords<T> q = Coords<T>::Zero();
  q(kB1) = unknowns(0);
  q(kB2) = unknowns(1);
  const Coords<T> v = Coords<T>::Zero();
  const DynamicsTerms<T> terms = ComputeDynamicsTerms<T>(p, q, v, unknowns(2), unknowns(3));
  const Coords<T> net = terms.generalized_thrust - terms.gravity_spring;
  return Eigen::Matrix<T, 4, 1>(net(kZ), net(kPhi), net(kB1), net(kB2));
}

}  // namespace

Equilibrium SolveHoverEquilibrium(const BirotorParams& p) {
  const double f0 = p.HoverForceN();
  const double b0 = (p.tip_mass_kg * p.gravity_m_s2 * p.arm_length_m - p.arm_length_m * f0) / p.arm_stiffness_n_m_rad;
  Eigen::Vector4d x(b0, -b0, f0, f0);
  Equilibrium eq;
  for (int iteration = 0; iteration < 50; ++iteration) {
    Eigen::Matrix<Jet4, 4, 1> xj;
    for (int i = 0; i < 4; ++i) xj(i) = Jet4(x(i), i);
    const Eigen::Matrix<Jet4, 4, 1> r = StaticResidual<Jet4>(p, xj);
    Eigen::Vector4d value;
    Eigen::Matrix4d jacobian;
    for (int i = 0; i < 4; ++i) {
      value(i) = r(i).a;
      jacobian.row(i) = r(i).v.transpose();
    }
    eq.residual = value.cwiseAbs().maxCoeff();
    if (eq.residual < 1e-12) {
      eq.converged = true;
      break;
    }
    x -= jacobian.partialPivLu().solve(value);
  }
  eq.deflection_rad[0] = x(0);
  eq.deflection_rad[1] = x(1);
  eq.force_n[0] = x(2);
  eq.force_n[1] = x(3);
  for (int i = 0; i < kBirotorRotors; ++i) eq.omega_rad_s[i] = std::sqrt(eq.force_n[i] / p.thrust_coeff_n_s2_rad2);
  return eq;
}

}  // namespace birotor
