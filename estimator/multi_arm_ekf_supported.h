// The N-arm EKF's process model while the ground holds the body (GroundContact,
// estimator/ground_contact.h): the members of MultiArmEkfModel<N> for an
// input with `supported` set, included through estimator/multi_arm_ekf_model_impl.h
// by the one-N translation units. The body is held still and level (x, z,
// phi and their rates do not change: phi_ddot = 0), and each arm obeys its
// own supported row of model/multi_arm_plant.h (MultiArmSupportedDerivative,
// the simulator's model on the ground) at phi = 0,
//   m_p L^2 b_ddot + d b_dot + k b + m_p g L cos(b + alpha) = l f
// (ClampedArmAcceleration, model/arm_dynamics.h). docs/estimator.md, "The EKF for N arms".
#pragma once

#include <ceres/jet.h>

#include "estimator/multi_arm_ekf_model.h"
#include "model/arm_dynamics.h"

namespace birotor {

template <int N>
template <typename T>
T MultiArmEkfModel<N>::SupportedArmAcceleration(int arm, const T& b, const T& b_dot, const T& force_n) const {
  const ArmDescription& a = vehicle_.arms[static_cast<size_t>(arm)];
  return ClampedArmAcceleration<T>(ClampedArmOf(vehicle_, arm), T(a.stiffness_n_m_rad), T(a.damping_n_m_s_rad),
                                   T(a.tip_mass_kg), b, b_dot, force_n);
}

template <int N>
typename MultiArmEkfModel<N>::Coordinates MultiArmEkfModel<N>::SupportedAcceleration(const State& x) const {
  Coordinates acc = Coordinates::Zero();  // x, z, phi held
  for (int i = 0; i < N; ++i) {
    acc(DeflectionIndex(i)) =
        SupportedArmAcceleration<double>(i, x(Layout::Deflection(i)), x(Layout::DeflectionRate(i)), Force(x, i));
  }
  return acc;
}

template <int N>
typename MultiArmEkfModel<N>::DynamicMatrix MultiArmEkfModel<N>::SupportedJacobian(const State& x, const Input& u,
                                                                                   State* x_dot) const {
  // Each arm's b_ddot on Jets over (b_i, b_dot_i, f_i), then the chain rule
  // through f_i = mu_i c_T,i omega_i^2 as in the free body's Jacobian. The
  // row phi_dot is 0 (the body is held), so A keeps the free body's block
  // and kinematic structure (Transition, Propagate).
  using Jet = ceres::Jet<double, 3>;
  const auto d = [](int state) { return Layout::Dynamic(state); };
  DynamicMatrix a = DynamicMatrix::Zero();
  Coordinates acc = Coordinates::Zero();
  for (int i = 0; i < N; ++i) {
    const Jet b_ddot = SupportedArmAcceleration<Jet>(i, Jet(x(Layout::Deflection(i)), 0),
                                                     Jet(x(Layout::DeflectionRate(i)), 1), Jet(Force(x, i), 2));
    acc(DeflectionIndex(i)) = b_ddot.a;
    const Eigen::Vector2d grad = ForceGradient(x, i);  // (df/domega, df/dmu)
    const int row = d(Layout::DeflectionRate(i));
    a(d(Layout::Deflection(i)), row) = 1.0;
    a(row, d(Layout::Deflection(i))) = b_ddot.v(0);
    a(row, row) = b_ddot.v(1);
    a(row, d(Layout::Omega(i))) = b_ddot.v(2) * grad(0);
    a(row, d(Layout::ThrustScale(i))) = b_ddot.v(2) * grad(1);
    a(d(Layout::Omega(i)), d(Layout::Omega(i))) = -1.0 / MotorTimeConstant(i);
  }
  if (x_dot != nullptr) *x_dot = DerivativeFrom(x, u, acc);
  return a;
}

}  // namespace birotor
