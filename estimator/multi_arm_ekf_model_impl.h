// The member definitions of MultiArmEkfModel<N> that are not inline in
// estimator/multi_arm_ekf_model.h, included only through
// estimator/multi_arm_ekf_impl.h by the one-N translation units
// estimator/multi_arm_ekf_n2.cc .. multi_arm_ekf_n6.cc, which instantiate it.
#pragma once

#include <array>

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
  // A dt has A's exact zeros (x dt = 0 only for x = 0 at the step's dt).
  const bool structured = HasRotorBlockStructure(a) && HasKinematicRows(a);
  if (blocks != nullptr) *blocks = structured;
  if (!structured) {  // not that structure: dense
    const DynamicMatrix a_dt = a * dt_s;
    DynamicMatrix phi = DynamicMatrix::Identity() + a_dt * 0.25;
    DynamicMatrix temp;
    for (const double c : {1.0 / 3.0, 0.5, 1.0}) {
      temp.noalias() = a_dt.lazyProduct(phi);
      phi = DynamicMatrix::Identity() + temp * c;
    }
    return phi;
  }
  // Phi_d = [F, G; 0, diag(e)], each block in its own contiguous matrix
  // through the series (the same products and sums as on Phi_d's blocks in
  // place, bit for bit, at 5/6 of the instructions), from A dt's blocks.
  constexpr int k = N, r = n - N;  // the kinematic rows b_i; the rows phi_dot, b_dot_i
  using ArmMatrix = Eigen::Matrix<double, n, n>;
  using CouplingMatrix = Eigen::Matrix<double, n, m>;
  using RotorVector = Eigen::Matrix<double, m, 1>;
  const Eigen::Matrix<double, r, n> a_ra = a.template block<r, n>(k, 0) * dt_s;
  const Eigen::Matrix<double, r, m> a_ru = a.template block<r, m>(k, n) * dt_s;
  const RotorVector d = a.template bottomRightCorner<m, m>().diagonal() * dt_s;
  std::array<double, k> a_kinematic;  // A dt's (b_i, b_dot_i)
  for (int i = 0; i < k; ++i) a_kinematic[static_cast<size_t>(i)] = a(i, k + 1 + i) * dt_s;
  const ArmMatrix a_aa = a.template topLeftCorner<n, n>() * dt_s;
  const CouplingMatrix a_au = a.template topRightCorner<n, m>() * dt_s;
  ArmMatrix f = ArmMatrix::Identity() + a_aa * 0.25;
  CouplingMatrix g = a_au * 0.25;
  RotorVector e = RotorVector::Ones() + d * 0.25;
  ArmMatrix temp_aa;
  CouplingMatrix temp_au;
  for (const double c : {1.0 / 3.0, 0.5, 1.0}) {
    for (int i = 0; i < k; ++i) {  // (A X)_(b_i) = A_(b_i, b_dot_i) X_(b_dot_i), A's other entries 0
      const int rate = k + 1 + i;
      temp_aa.row(i) = a_kinematic[static_cast<size_t>(i)] * f.row(rate);
      temp_au.row(i) = a_kinematic[static_cast<size_t>(i)] * g.row(rate);
    }
    temp_aa.template bottomRows<r>().noalias() = a_ra.lazyProduct(f);
    temp_au.template bottomRows<r>().noalias() = a_ra.lazyProduct(g);
    temp_au.template bottomRows<r>().noalias() += a_ru * e.asDiagonal();
    f = ArmMatrix::Identity() + temp_aa * c;
    g = temp_au * c;
    e = RotorVector::Ones() + d.cwiseProduct(e) * c;
  }
  DynamicMatrix phi = DynamicMatrix::Zero();
  phi.template topLeftCorner<n, n>() = f;
  phi.template topRightCorner<n, m>() = g;
  phi.template bottomRightCorner<m, m>().diagonal() = e;
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
