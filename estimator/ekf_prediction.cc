// The EKF's prediction step (members of EkfForceEstimator): the state by
// RK4 and the covariance propagated on the live states only (LiveStates:
// the rest of P is zero and stays zero), docs/mismatch.md "Cost".
#include "estimator/ekf_force_estimator.h"

namespace birotor {

void EkfForceEstimator::Predict(double dt_s, const EkfInput& input) {
  // Linearise at the prior, then propagate the state with RK4 and
  // P = Phi P Phi^T + Qc dt (PropagateCovariance).
  DynamicVector mass_column;
  const DynamicMatrix a =
      process_.Jacobian(state_, input, &accel_linearization_, process_.body_mass_is_state() ? &mass_column : nullptr);
  const DynamicMatrix phi = EkfProcessModel::Transition(a, dt_s);
  state_ = process_.Step(state_, input, dt_s);
  switch (LiveStates()) {
    case kStrainScale1:
      PropagateCovariance<kStrainScale1>(phi, nullptr, dt_s);
      return;
    case kBodyMassScale:
      PropagateCovariance<kBodyMassScale>(phi, nullptr, dt_s);
      return;
    default:
      if (process_.body_mass_is_state() && !input.body_supported) {
        const DynamicVector gamma = EkfProcessModel::ParameterTransition(a, mass_column, dt_s);
        PropagateCovariance<kEkfStateSize>(phi, &gamma, dt_s);
      } else {
        PropagateCovariance<kEkfStateSize>(phi, nullptr, dt_s);
      }
  }
}

template <int N>
void EkfForceEstimator::PropagateCovariance(const DynamicMatrix& phi, const DynamicVector* gamma, double dt_s) {
  // Phi = [Phi_d, Gamma; 0, I] (the offsets and slow states are random walks;
  // Gamma is the body mass's column, zero unless learned) on the N live
  // states; the rest of P is zero and stays zero (no noise, LiveStates):
  //   R_d = Phi_d P_dd + Gamma P_md, R_s = Phi_d P_ds + Gamma P_ms,
  //   P_dd = R_d Phi_d^T + R_s,m Gamma^T, P_ds = R_s, P_ss kept.
  constexpr int n = kDynamicStateSize, m = N - kDynamicStateSize;
  DynamicMatrix temp;
  temp.noalias() = phi.lazyProduct(covariance_.topLeftCorner<n, n>());
  Eigen::Matrix<double, n, m> p_ds;
  p_ds.noalias() = phi.lazyProduct(covariance_.block<n, m>(0, n));
  if constexpr (N == kEkfStateSize) {
    if (gamma != nullptr) {
      constexpr int mass = kBodyMassScale - kDynamicStateSize;  // its column in the slow block
      temp.noalias() += *gamma * covariance_.block<1, n>(kBodyMassScale, 0);
      p_ds.noalias() += *gamma * covariance_.block<1, m>(kBodyMassScale, n);
      covariance_.topLeftCorner<n, n>().noalias() = temp.lazyProduct(phi.transpose());
      covariance_.topLeftCorner<n, n>().noalias() += p_ds.col(mass) * gamma->transpose();
    } else {
      covariance_.topLeftCorner<n, n>().noalias() = temp.lazyProduct(phi.transpose());
    }
  } else {
    covariance_.topLeftCorner<n, n>().noalias() = temp.lazyProduct(phi.transpose());
  }
  covariance_.block<n, m>(0, n) = p_ds;
  covariance_.block<m, n>(n, 0) = p_ds.transpose();
  covariance_.diagonal().head<N>() += process_noise_psd_.head<N>() * dt_s;
}

}  // namespace birotor
