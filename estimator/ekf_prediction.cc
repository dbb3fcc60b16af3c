// The EKF's prediction step (members of EkfForceEstimator): the state by
// RK4 and the covariance propagated on the live states only (LiveStates:
// the rest of P is zero and stays zero), docs/mismatch.md "Cost".
#include "estimator/ekf_force_estimator.h"

namespace birotor {
namespace {

constexpr int kArm = kOmega1, kRotor = kDynamicStateSize - kOmega1;  // arm states; omega and mu

// Phi_d X for a 9 x C matrix X, on those blocks when blocks (the same sums
// less Phi's exact zeros: about half the dense product).
template <int C, typename X>
Eigen::Matrix<double, kDynamicStateSize, C> TransitionTimes(const DynamicMatrix& phi, const Eigen::MatrixBase<X>& x,
                                                            bool blocks) {
  Eigen::Matrix<double, kDynamicStateSize, C> out;
  if (!blocks) {
    out.noalias() = phi.lazyProduct(x);
    return out;
  }
  auto top = out.template topRows<kArm>();
  top.noalias() = phi.topLeftCorner<kArm, kArm>().lazyProduct(x.template topRows<kArm>());
  top.noalias() += phi.topRightCorner<kArm, kRotor>().lazyProduct(x.template bottomRows<kRotor>());
  out.template bottomRows<kRotor>() =
      phi.bottomRightCorner<kRotor, kRotor>().diagonal().asDiagonal() * x.template bottomRows<kRotor>();
  return out;
}

}  // namespace

bool EkfProcessModel::HasRotorBlockStructure(const DynamicMatrix& x) {
  constexpr int m = kDynamicStateSize - kOmega1;  // omega and mu
  Eigen::Matrix<double, m, kDynamicStateSize> rows = x.bottomRows<m>();
  rows.rightCols<m>().diagonal().setZero();
  // sum |x_ij| over those entries is 0 exactly when each is +-0: a NaN or an
  // infinity makes it NaN or inf, and no positive term is lost (the sum is
  // at least the largest term).
  return rows.cwiseAbs().sum() == 0.0 && !x.diagonal().tail<m>().array().isInf().any();
}

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
  // Phi_d has A's block structure (EkfProcessModel::Transition: the motor lag
  // and the thrust scales do not depend on the arms).
  const bool blocks = EkfProcessModel::HasRotorBlockStructure(phi);
  DynamicMatrix temp = TransitionTimes<n>(phi, covariance_.topLeftCorner<n, n>(), blocks);
  Eigen::Matrix<double, n, m> p_ds = TransitionTimes<m>(phi, covariance_.block<n, m>(0, n), blocks);
  if constexpr (N == kEkfStateSize) {
    if (gamma != nullptr) {
      temp.noalias() += *gamma * covariance_.block<1, n>(kBodyMassScale, 0);
      p_ds.noalias() += *gamma * covariance_.block<1, m>(kBodyMassScale, n);
    }
  }
  // P_dd = R_d Phi_d^T = (Phi_d R_d^T)^T.
  covariance_.topLeftCorner<n, n>() = TransitionTimes<n>(phi, temp.transpose(), blocks).transpose();
  if constexpr (N == kEkfStateSize) {
    constexpr int mass = kBodyMassScale - kDynamicStateSize;  // its column in the slow block
    if (gamma != nullptr) covariance_.topLeftCorner<n, n>().noalias() += p_ds.col(mass) * gamma->transpose();
  }
  covariance_.block<n, m>(0, n) = p_ds;
  covariance_.block<m, n>(n, 0) = p_ds.transpose();
  covariance_.diagonal().head<N>() += process_noise_psd_.head<N>() * dt_s;
}

}  // namespace birotor
