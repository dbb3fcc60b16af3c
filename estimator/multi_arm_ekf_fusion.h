// The fusion of estimator/kalman_fusion.h (innovation, chi-square gate,
// Kalman gain, Joseph covariance) on all states of a symmetric P, its Joseph
// terms grouped: the N-arm EKF's accelerometer, and its
// motor telemetry (omega_i) and gyro (phi_dot), whose rows of H read one
// state each (H's zeros left out of the products). Header-only and fixed-size: no
// allocation, no throw, no log. docs/estimator.md, "The EKF for N arms".
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <array>

#include "estimator/fusion_report.h"
#include "estimator/kalman_fusion.h"

namespace birotor {

// The state each row of H reads: the column of its 1 (H's row j is the unit
// row e_s^T), or -1 for a zero row (a masked entry, MultiArmMeasurements).
// H's rows must be unit or zero rows.
template <int M, int N>
std::array<int, M> UnitRowStates(const Eigen::Matrix<double, M, N>& h) {
  std::array<int, M> states;
  states.fill(-1);
  for (int j = 0; j < M; ++j) {
    for (int c = 0; c < N; ++c) {
      if (h(j, c) != 0.0) states[static_cast<size_t>(j)] = c;
    }
  }
  return states;
}

// The update after the gate, from H P, S^-1 and y = z - h: K = (H P)^T S^-1,
// x += K y, A = P - K (H P) and
//   P+ = A (I - K H)^T + K R K^T = A - (A H^T - K R) K^T,
// the Joseph form (the same product as JosephCovariance, its last two terms
// as one: they share the factor K^T); a_ht(A) gives A H^T. Not symmetrised
// here (as JosephCovariance; the N-arm EKF symmetrises P once per strain
// sample). The rounding differs from JosephCovariance's by the grouping only.
template <int M, typename State, typename Cov, typename AHt>
void GroupedJosephUpdate(const Eigen::Matrix<double, M, State::RowsAtCompileTime>& h_p,
                         const Eigen::Matrix<double, M, M>& s_inverse, const Eigen::Matrix<double, M, 1>& residual,
                         const Eigen::Matrix<double, M, M>& noise, State* x, Cov* cov, AHt&& a_ht) {
  constexpr int N = State::RowsAtCompileTime;
  Eigen::Matrix<double, N, M> gain;
  gain.noalias() = h_p.transpose().lazyProduct(s_inverse);
  x->noalias() += gain.lazyProduct(residual);
  Eigen::Matrix<double, N, N> a = *cov;
  a.noalias() -= gain.lazyProduct(h_p);  // (I - K H) P
  Eigen::Matrix<double, N, M> a_ht_minus_kr = a_ht(a);
  a_ht_minus_kr.noalias() -= gain.lazyProduct(noise);
  a.noalias() -= a_ht_minus_kr.lazyProduct(gain.transpose());
  *cov = a;
}

// FuseMeasurementUnreported on all N states of x and a symmetric P, with the
// covariance by GroupedJosephUpdate: S = H P H^T + R, NIS = y^T S^-1 y, gated
// as there (the N-arm accelerometer).
template <int M, typename State, typename Cov>
FusionOutcome FuseSymmetricUnreported(const MeasurementLinearization<M, State::RowsAtCompileTime>& at,
                                      const Eigen::Matrix<double, M, M>& noise, const Eigen::Matrix<double, M, 1>& z,
                                      double gate_nis, State* x, Cov* cov, double* nis = nullptr) {
  constexpr int N = State::RowsAtCompileTime;
  Eigen::Matrix<double, M, N> h_p;
  h_p.noalias() = at.jacobian.lazyProduct(*cov);
  Eigen::Matrix<double, M, M> s = noise;
  s.noalias() += h_p.lazyProduct(at.jacobian.transpose());
  const Eigen::Matrix<double, M, 1> residual = z - at.predicted;
  const Eigen::Matrix<double, M, M> s_inverse = s.inverse();
  const double nis_value = residual.dot(s_inverse * residual);
  if (nis != nullptr) *nis = nis_value;
  if (!(nis_value <= gate_nis)) return FusionOutcome::kRejectedGate;  // a NaN NIS is rejected too
  GroupedJosephUpdate(h_p, s_inverse, residual, noise, x, cov, [&at](const Eigen::Matrix<double, N, N>& a) {
    Eigen::Matrix<double, N, M> a_ht;
    a_ht.noalias() = a.lazyProduct(at.jacobian.transpose());
    return a_ht;
  });
  return FusionOutcome::kFused;
}

// FuseSymmetricUnreported for H of unit or zero rows (UnitRowStates; the
// N-arm telemetry and gyro), H's zeros left out: with s_j the state row j
// reads, H P is P's rows s_j, H P H^T their columns s_l, A H^T A's columns s_j.
template <int M, typename State, typename Cov>
FusionOutcome FuseUnitRowsUnreported(const MeasurementLinearization<M, State::RowsAtCompileTime>& at,
                                     const Eigen::Matrix<double, M, M>& noise, const Eigen::Matrix<double, M, 1>& z,
                                     double gate_nis, State* x, Cov* cov, double* nis = nullptr) {
  constexpr int N = State::RowsAtCompileTime;
  const std::array<int, M> states = UnitRowStates(at.jacobian);
  Eigen::Matrix<double, M, N> h_p = Eigen::Matrix<double, M, N>::Zero();
  Eigen::Matrix<double, M, M> s = noise;
  for (int j = 0; j < M; ++j) {
    const int row = states[static_cast<size_t>(j)];
    if (row < 0) continue;
    h_p.row(j) = cov->row(row);
    for (int l = 0; l < M; ++l) {
      const int col = states[static_cast<size_t>(l)];
      if (col >= 0) s(j, l) += h_p(j, col);
    }
  }
  const Eigen::Matrix<double, M, 1> residual = z - at.predicted;
  const Eigen::Matrix<double, M, M> s_inverse = s.inverse();
  const double nis_value = residual.dot(s_inverse * residual);
  if (nis != nullptr) *nis = nis_value;
  if (!(nis_value <= gate_nis)) return FusionOutcome::kRejectedGate;  // a NaN NIS is rejected too
  GroupedJosephUpdate(h_p, s_inverse, residual, noise, x, cov, [&states](const Eigen::Matrix<double, N, N>& a) {
    Eigen::Matrix<double, N, M> a_ht = Eigen::Matrix<double, N, M>::Zero();
    for (int j = 0; j < M; ++j) {
      if (states[static_cast<size_t>(j)] >= 0) a_ht.col(j) = a.col(states[static_cast<size_t>(j)]);
    }
    return a_ht;
  });
  return FusionOutcome::kFused;
}

}  // namespace birotor
