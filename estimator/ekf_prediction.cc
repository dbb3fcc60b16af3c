// The EKF's prediction step (members of EkfForceEstimator): the state by
// RK4, the transition matrix (EkfProcessModel::Transition) and the
// covariance propagated on the live states only (LiveStates: the rest of P
// is zero and stays zero), docs/mismatch.md "Cost".
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

// Gamma = W c dt on W's blocks [W_aa, W_au; 0, D] (D diagonal).
void ParameterColumn(const DynamicMatrix& w, const DynamicVector& c, double dt_s, DynamicVector* gamma) {
  auto arm = gamma->head<kArm>();
  arm.noalias() = w.topLeftCorner<kArm, kArm>().lazyProduct(c.head<kArm>());
  arm.noalias() += w.topRightCorner<kArm, kRotor>().lazyProduct(c.tail<kRotor>());
  gamma->tail<kRotor>() = w.bottomRightCorner<kRotor, kRotor>().diagonal().cwiseProduct(c.tail<kRotor>());
  *gamma *= dt_s;
}

}  // namespace

// The rows of omega and mu exactly +-0 left of D and off its diagonal: the
// same answer as bottomLeftCorner().isZero(0.0) &&
// bottomRightCorner().isDiagonal(0.0), which also says no for an infinite
// entry of D (max |D_ii| times the precision 0 is NaN), at a third of the
// instructions; it runs twice per prediction (Transition, PropagateCovariance).
bool EkfProcessModel::HasRotorBlockStructure(const DynamicMatrix& x) {
  constexpr int m = kDynamicStateSize - kOmega1;  // omega and mu
  Eigen::Matrix<double, m, kDynamicStateSize> rows = x.bottomRows<m>();
  rows.rightCols<m>().diagonal().setZero();
  // sum |x_ij| over those entries is 0 exactly when each is +-0: a NaN or an
  // infinity makes it NaN or inf, and no positive term is lost (the sum is
  // at least the largest term).
  return rows.cwiseAbs().sum() == 0.0 && !x.diagonal().tail<m>().array().isInf().any();
}

DynamicMatrix EkfProcessModel::Transition(const DynamicMatrix& a, double dt_s, const DynamicVector* column,
                                          DynamicVector* gamma) {
  // Horner form: I + A dt (I + A dt/2 (I + A dt/3 (I + A dt/4))), lazyProduct (faster than GEMM at 9x9).
  // A = [A_aa, A_au; 0, D] (the rows of omega and mu are the diagonal motor lag and zero), so is every
  // power: the steps run on its blocks (a third of the cost, the same sums less A's exact zeros).
  constexpr int n = kOmega1, m = kDynamicStateSize - kOmega1;  // arm states; omega and mu
  const DynamicMatrix a_dt = a * dt_s;
  DynamicMatrix phi = DynamicMatrix::Identity() + a_dt * 0.25;
  const auto d = a_dt.bottomRightCorner<m, m>();
  if (!HasRotorBlockStructure(a_dt)) {  // not that structure: dense
    DynamicMatrix temp;
    for (const double c : {1.0 / 3.0, 0.5, 1.0}) {
      if (c == 1.0 && gamma != nullptr) gamma->noalias() = phi.lazyProduct(*column) * dt_s;  // phi is W here
      temp.noalias() = a_dt.lazyProduct(phi);
      phi = DynamicMatrix::Identity() + temp * c;
    }
    return phi;
  }
  const auto a_aa = a_dt.topLeftCorner<n, n>();
  const auto a_au = a_dt.topRightCorner<n, m>();
  Eigen::Matrix<double, n, n> temp_aa;
  Eigen::Matrix<double, n, m> temp_au;
  for (const double c : {1.0 / 3.0, 0.5, 1.0}) {
    if (c == 1.0 && gamma != nullptr) ParameterColumn(phi, *column, dt_s, gamma);  // phi is W here
    temp_aa.noalias() = a_aa.lazyProduct(phi.topLeftCorner<n, n>());
    temp_au.noalias() = a_aa.lazyProduct(phi.topRightCorner<n, m>());
    temp_au.noalias() += a_au * phi.bottomRightCorner<m, m>().diagonal().asDiagonal();
    phi.topLeftCorner<n, n>() = Eigen::Matrix<double, n, n>::Identity() + temp_aa * c;
    phi.topRightCorner<n, m>() = temp_au * c;
    phi.bottomRightCorner<m, m>().diagonal() =
        Eigen::Matrix<double, m, 1>::Ones() + d.diagonal().cwiseProduct(phi.bottomRightCorner<m, m>().diagonal()) * c;
  }
  return phi;
}

void EkfForceEstimator::Predict(double dt_s, const EkfInput& input) {
  // Linearise at the prior, then propagate the state with RK4 and
  // P = Phi P Phi^T + Qc dt (PropagateCovariance).
  DynamicVector mass_column;
  const DynamicMatrix a =
      process_.Jacobian(state_, input, &accel_linearization_, process_.body_mass_is_state() ? &mass_column : nullptr);
  // Gamma, the body mass's column of the transition, only while the mass is
  // live in free flight (from Phi_d's Horner factor: the same polynomial).
  const bool mass_column_needed =
      LiveStates() == kEkfStateSize && process_.body_mass_is_state() && !input.body_supported;
  DynamicVector gamma;
  const DynamicMatrix phi = EkfProcessModel::Transition(a, dt_s, &mass_column, mass_column_needed ? &gamma : nullptr);
  state_ = process_.Step(state_, input, dt_s);
  switch (LiveStates()) {
    case kStrainScale1:
      PropagateCovariance<kStrainScale1>(phi, nullptr, dt_s);
      return;
    case kBodyMassScale:
      PropagateCovariance<kBodyMassScale>(phi, nullptr, dt_s);
      return;
    default:
      if (mass_column_needed) {
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
  // Gamma's rows of omega and mu are zero when c's are (the mass does not
  // enter the motor lag) and W has the block structure: the outer products
  // with Gamma on its arm rows only (the same sums less those exact zeros).
  const bool gamma_on_arms = gamma != nullptr && gamma->tail<kRotor>().isZero(0.0);
  if constexpr (N == kEkfStateSize) {
    if (gamma_on_arms) {
      temp.topRows<kArm>().noalias() += gamma->head<kArm>() * covariance_.block<1, n>(kBodyMassScale, 0);
      p_ds.template topRows<kArm>().noalias() += gamma->head<kArm>() * covariance_.block<1, m>(kBodyMassScale, n);
    } else if (gamma != nullptr) {
      temp.noalias() += *gamma * covariance_.block<1, n>(kBodyMassScale, 0);
      p_ds.noalias() += *gamma * covariance_.block<1, m>(kBodyMassScale, n);
    }
  }
  // P_dd = R_d Phi_d^T = (Phi_d R_d^T)^T.
  covariance_.topLeftCorner<n, n>() = TransitionTimes<n>(phi, temp.transpose(), blocks).transpose();
  if constexpr (N == kEkfStateSize) {
    constexpr int mass = kBodyMassScale - kDynamicStateSize;  // its column in the slow block
    if (gamma_on_arms) {
      covariance_.topLeftCorner<n, kArm>().noalias() += p_ds.col(mass) * gamma->head<kArm>().transpose();
    } else if (gamma != nullptr) {
      covariance_.topLeftCorner<n, n>().noalias() += p_ds.col(mass) * gamma->transpose();
    }
  }
  covariance_.block<n, m>(0, n) = p_ds;
  covariance_.block<m, n>(n, 0) = p_ds.transpose();
  covariance_.diagonal().head<N>() += process_noise_psd_.head<N>() * dt_s;
}

}  // namespace birotor
