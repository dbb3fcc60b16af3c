// The member definitions of MultiArmEkfModel<N> that are not inline in
// estimator/multi_arm_ekf_model.h, included only through
// estimator/multi_arm_ekf_impl.h by the one-N translation units
// estimator/multi_arm_ekf_n2.cc .. multi_arm_ekf_n6.cc, which instantiate it.
#pragma once

#include "estimator/multi_arm_ekf_model.h"
#include "estimator/multi_arm_ekf_supported.h"

namespace birotor {

template <int N>
bool MultiArmEkfModel<N>::HasRotorBlockStructure(const DynamicMatrix& x) {
  // sum |x_ij| over the rotor rows left of D and off its diagonal is 0
  // exactly when each is +-0 (a NaN or an infinity makes it NaN or inf).
  Eigen::Matrix<double, kRotorStates, kD> rows = x.template bottomRows<kRotorStates>();
  rows.template rightCols<kRotorStates>().diagonal().setZero();
  return rows.cwiseAbs().sum() == 0.0 && x.diagonal().template tail<kRotorStates>().allFinite();
}

template <int N>
typename MultiArmEkfModel<N>::DynamicMatrix MultiArmEkfModel<N>::Transition(const DynamicMatrix& a, double dt_s,
                                                                            bool* blocks) {
  constexpr int n = kArmStates, m = kRotorStates;
  const DynamicMatrix a_dt = a * dt_s;
  DynamicMatrix phi = DynamicMatrix::Identity() + a_dt * 0.25;
  const bool structured = HasRotorBlockStructure(a_dt) && HasKinematicRows(a_dt);
  if (blocks != nullptr) *blocks = structured;
  if (!structured) {  // not that structure: dense
    DynamicMatrix temp;
    for (const double c : {1.0 / 3.0, 0.5, 1.0}) {
      temp.noalias() = a_dt.lazyProduct(phi);
      phi = DynamicMatrix::Identity() + temp * c;
    }
    return phi;
  }
  constexpr int k = N, r = n - N;  // the kinematic rows b_i; the rows phi_dot, b_dot_i
  const auto a_ra = a_dt.template block<r, n>(k, 0);
  const auto a_ru = a_dt.template block<r, m>(k, n);
  const Eigen::Matrix<double, m, 1> d = a_dt.template bottomRightCorner<m, m>().diagonal();
  Eigen::Matrix<double, n, n> temp_aa;
  Eigen::Matrix<double, n, m> temp_au;
  for (const double c : {1.0 / 3.0, 0.5, 1.0}) {
    for (int i = 0; i < k; ++i) {  // (A X)_(b_i) = A_(b_i, b_dot_i) X_(b_dot_i), A's other entries 0
      const int rate = k + 1 + i;
      temp_aa.row(i) = a_dt(i, rate) * phi.template block<1, n>(rate, 0);
      temp_au.row(i) = a_dt(i, rate) * phi.template block<1, m>(rate, n);
    }
    temp_aa.template bottomRows<r>().noalias() = a_ra.lazyProduct(phi.template topLeftCorner<n, n>());
    temp_au.template bottomRows<r>().noalias() = a_ra.lazyProduct(phi.template topRightCorner<n, m>());
    temp_au.template bottomRows<r>().noalias() += a_ru * phi.template bottomRightCorner<m, m>().diagonal().asDiagonal();
    phi.template topLeftCorner<n, n>() = Eigen::Matrix<double, n, n>::Identity() + temp_aa * c;
    phi.template topRightCorner<n, m>() = temp_au * c;
    phi.template bottomRightCorner<m, m>().diagonal() =
        Eigen::Matrix<double, m, 1>::Ones() + d.cwiseProduct(phi.template bottomRightCorner<m, m>().diagonal()) * c;
  }
  return phi;
}

template <int N>
bool MultiArmEkfModel<N>::HasKinematicRows(const DynamicMatrix& x) {
  // The rows b_i: exactly +-0 but at the column b_dot_i (index N + 1 + i).
  Eigen::Matrix<double, N, kD> rows = x.template topRows<N>();
  for (int i = 0; i < N; ++i) rows(i, N + 1 + i) = 0.0;
  return rows.cwiseAbs().sum() == 0.0;
}

}  // namespace birotor
