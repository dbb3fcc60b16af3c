// The fusion of estimator/kalman_fusion.h (innovation, chi-square gate,
// Kalman gain, Joseph covariance) on all states of a symmetric P, its Joseph
// terms grouped and formed on P's upper triangle: the N-arm EKF's
// accelerometer (H dense but for its leading zero columns, the offsets e_i),
// and its strain (b_i + e_i), motor telemetry (omega_i) and gyro (phi_dot),
// whose rows of H are sums of at most two unit rows (H's zeros left out of
// the products). Header-only and fixed-size: no allocation, no throw, no log.
// docs/estimator.md, "The EKF for N arms".
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <array>

#include "estimator/fusion_report.h"
#include "estimator/kalman_fusion.h"

namespace birotor {

// The states each row of H reads: row j is e_a^T + e_b^T with
// states[j] = {a, b}, b = -1 for a unit row e_a^T, a = b = -1 for a zero row
// (a masked entry, MultiArmMeasurements). H's entries must be 0 or 1, at
// most two 1s a row.
// A Schmidt hold on the leading R states of the update (SymmetricJosephUpdate):
// keep = I - U U^T for the orthonormal columns U of the combinations that
// are not to be updated. Inactive: the optimal gain, unchanged.
template <int R>
struct LeadingGainHold {
  bool active = false;
  Eigen::Matrix<double, R, R> keep = Eigen::Matrix<double, R, R>::Identity();
};

// A Schmidt hold on single states among the trailing T of the update: the
// gain's row of trailing state j scaled by keep(j), 1 updated, 0 held (the
// N-arm EKF's thrust scales mu_i, its last N states). Inactive: unchanged.
template <int T>
struct TrailingGainHold {
  bool active = false;
  Eigen::Matrix<double, T, 1> keep = Eigen::Matrix<double, T, 1>::Ones();
};

template <int M>
using OnesRowStates = std::array<std::array<int, 2>, M>;

template <int M, int N>
OnesRowStates<M> FindOnesRowStates(const Eigen::Matrix<double, M, N>& h) {
  OnesRowStates<M> states;
  for (int j = 0; j < M; ++j) {
    std::array<int, 2>& row = states[static_cast<size_t>(j)];
    row = {-1, -1};
    size_t found = 0;
    for (int c = 0; c < N && found < row.size(); ++c) {
      if (h(j, c) != 0.0) row[found++] = c;
    }
  }
  return states;
}

// The update after the gate on a symmetric P (n states, m measured), from
// H P, S = H P H^T + R, S^-1 and y = z - h: K = (H P)^T S^-1, x += K y, and
// the Joseph form
//   P+ = (I - K H) P (I - K H)^T + K R K^T = A - B K^T,  A = P - K (H P),
//   B = A H^T - K R = (H P)^T - K (H P H^T) - K R = (H P)^T - K S
// (exact algebra: A H^T = P H^T - K H P H^T, so A's n x n product is not
// formed; B is K's rounding away from the optimal gain, as in JosephCovariance).
// P+ is symmetric when P is: each pair (r, c), (c, r) is computed once, on the
// upper triangle column by column, and mirrored, n (n + 1) / 2 entries of 2 m
// products each instead of 2 n^2. P+_rc = P_rc - K_r . (H P)_c - B_r . K_c.
//
// hold, when not null and active: a Schmidt (consider) update of the leading
// R states, the gain's first R rows replaced by hold->keep times them (the
// combinations hold->keep removes are not moved; their variance and
// correlations stay in P, exact for this gain: the Joseph form holds for any
// gain, and B = (H P)^T - K S is A H^T - K R for any K); tail, likewise,
// the gain's last T rows scaled by tail->keep.
template <int M, typename State, typename Cov, int R = 1, int T = 1>
void SymmetricJosephUpdate(const Eigen::Matrix<double, M, State::RowsAtCompileTime>& h_p,
                           const Eigen::Matrix<double, M, M>& s, const Eigen::Matrix<double, M, M>& s_inverse,
                           const Eigen::Matrix<double, M, 1>& residual, State* x, Cov* cov,
                           const LeadingGainHold<R>* hold = nullptr, const TrailingGainHold<T>* tail = nullptr) {
  constexpr int N = State::RowsAtCompileTime;
  Eigen::Matrix<double, N, M> gain;
  gain.noalias() = h_p.transpose().lazyProduct(s_inverse);
  if (hold != nullptr && hold->active) {
    const Eigen::Matrix<double, R, M> leading = hold->keep * gain.template topRows<R>();
    gain.template topRows<R>() = leading;
  }
  if (tail != nullptr && tail->active)
    gain.template bottomRows<T>() = tail->keep.asDiagonal() * gain.template bottomRows<T>();
  x->noalias() += gain.lazyProduct(residual);
  Eigen::Matrix<double, N, M> b = h_p.transpose();
  b.noalias() -= gain.lazyProduct(s);
  for (int c = 0; c < N; ++c) {
    // Column c's factors, then its rows 0 .. c: a plain loop over r with the
    // m terms unrolled, which the compiler vectorises (Eigen's products on a
    // run-time head(c + 1) do not).
    std::array<double, M> h_p_c, gain_c;
    for (int k = 0; k < M; ++k) {
      h_p_c[static_cast<size_t>(k)] = h_p(k, c);
      gain_c[static_cast<size_t>(k)] = gain(c, k);
    }
    for (int r = 0; r <= c; ++r) {
      double kalman = 0.0, joseph = 0.0;  // K_r . (H P)_c and B_r . K_c, summed in k's order
      for (int k = 0; k < M; ++k) kalman += gain(r, k) * h_p_c[static_cast<size_t>(k)];
      for (int k = 0; k < M; ++k) joseph += b(r, k) * gain_c[static_cast<size_t>(k)];
      (*cov)(r, c) = (*cov)(r, c) - kalman - joseph;
    }
    for (int r = 0; r < c; ++r) (*cov)(c, r) = (*cov)(r, c);
  }
}

// What a grouped fusion hands out when asked (report not null): y, the
// diagonal of S and the NIS (FusionReport; the caller sets source, utime
// and, for a masked entry, its variance 0).
template <int M>
void FillFusionReport(const Eigen::Matrix<double, M, 1>& residual, const Eigen::Matrix<double, M, M>& s, double nis,
                      double gate_nis, FusionOutcome outcome, FusionReport* report) {
  static_assert(M <= kMaxMeasurementSize, "FusionReport holds at most kMaxMeasurementSize values");
  report->size = M;
  report->innovation.template head<M>() = residual;
  report->innovation_variance.template head<M>() = s.diagonal();
  report->nis = nis;
  report->gate = gate_nis;
  report->outcome = outcome;
}

// The gate after S: NIS = y^T S^-1 y; a NaN NIS is rejected too.
template <int M>
bool PassesGate(const Eigen::Matrix<double, M, M>& s_inverse, const Eigen::Matrix<double, M, 1>& residual,
                double gate_nis, double* nis) {
  const double nis_value = residual.dot(s_inverse * residual);
  if (nis != nullptr) *nis = nis_value;
  return nis_value <= gate_nis;
}

// The gate on S and, when it passes, SymmetricJosephUpdate; *nis and
// *report filled when not null (the tail of every grouped fusion).
template <int M, typename State, typename Cov, int R = 1, int T = 1>
FusionOutcome GateAndUpdate(const Eigen::Matrix<double, M, State::RowsAtCompileTime>& h_p,
                            const Eigen::Matrix<double, M, M>& s, const Eigen::Matrix<double, M, 1>& residual,
                            double gate_nis, State* x, Cov* cov, double* nis, FusionReport* report,
                            const LeadingGainHold<R>* hold = nullptr, const TrailingGainHold<T>* tail = nullptr) {
  const Eigen::Matrix<double, M, M> s_inverse = s.inverse();
  double nis_value;
  const bool passes = PassesGate(s_inverse, residual, gate_nis, &nis_value);
  if (nis != nullptr) *nis = nis_value;
  const FusionOutcome outcome = passes ? FusionOutcome::kFused : FusionOutcome::kRejectedGate;
  if (report != nullptr) FillFusionReport(residual, s, nis_value, gate_nis, outcome, report);
  if (passes) SymmetricJosephUpdate(h_p, s, s_inverse, residual, x, cov, hold, tail);
  return outcome;
}

// FuseMeasurementUnreported on all N states of x and a symmetric P, with the
// covariance by SymmetricJosephUpdate: S = H P H^T + R, NIS = y^T S^-1 y,
// gated as there (the N-arm accelerometer). H's first Z columns must be zero
// (the accelerometer reads no offset e_i): left out of H P and H P H^T.
// report, when not null: FillFusionReport; hold, tail: SymmetricJosephUpdate's.
template <int Z = 0, int M, typename State, typename Cov, int R = 1, int T = 1>
FusionOutcome FuseSymmetricUnreported(const MeasurementLinearization<M, State::RowsAtCompileTime>& at,
                                      const Eigen::Matrix<double, M, M>& noise, const Eigen::Matrix<double, M, 1>& z,
                                      double gate_nis, State* x, Cov* cov, double* nis = nullptr,
                                      FusionReport* report = nullptr, const LeadingGainHold<R>* hold = nullptr,
                                      const TrailingGainHold<T>* tail = nullptr) {
  constexpr int N = State::RowsAtCompileTime, read = N - Z;
  const auto h_read = at.jacobian.template rightCols<read>();
  Eigen::Matrix<double, M, N> h_p;
  h_p.noalias() = h_read.lazyProduct(cov->template bottomRows<read>());
  Eigen::Matrix<double, M, M> s = noise;
  s.noalias() += h_p.template rightCols<read>().lazyProduct(h_read.transpose());
  const Eigen::Matrix<double, M, 1> residual = z - at.predicted;
  return GateAndUpdate(h_p, s, residual, gate_nis, x, cov, nis, report, hold, tail);
}

// FuseSymmetricUnreported for H whose rows are sums of at most two unit rows
// (FindOnesRowStates; the N-arm strain b_i + e_i, telemetry and gyro), H's
// zeros left out: with {a_j, b_j} the states row j reads, (H P)_j = P_(a_j) +
// P_(b_j) (rows), (H P H^T)_jl = (H P)_(j, a_l) + (H P)_(j, b_l).
// report, when not null: FillFusionReport; hold, tail: SymmetricJosephUpdate's.
template <int M, typename State, typename Cov, int R = 1, int T = 1>
FusionOutcome FuseOnesRowsUnreported(const MeasurementLinearization<M, State::RowsAtCompileTime>& at,
                                     const Eigen::Matrix<double, M, M>& noise, const Eigen::Matrix<double, M, 1>& z,
                                     double gate_nis, State* x, Cov* cov, double* nis = nullptr,
                                     FusionReport* report = nullptr, const LeadingGainHold<R>* hold = nullptr,
                                     const TrailingGainHold<T>* tail = nullptr) {
  constexpr int N = State::RowsAtCompileTime;
  const OnesRowStates<M> states = FindOnesRowStates(at.jacobian);
  Eigen::Matrix<double, M, N> h_p = Eigen::Matrix<double, M, N>::Zero();
  for (int j = 0; j < M; ++j) {
    for (const int state : states[static_cast<size_t>(j)]) {
      if (state >= 0) h_p.row(j) += cov->row(state);
    }
  }
  Eigen::Matrix<double, M, M> s = noise;
  for (int j = 0; j < M; ++j) {
    for (int l = 0; l < M; ++l) {
      for (const int state : states[static_cast<size_t>(l)]) {
        if (state >= 0) s(j, l) += h_p(j, state);
      }
    }
  }
  const Eigen::Matrix<double, M, 1> residual = z - at.predicted;
  return GateAndUpdate(h_p, s, residual, gate_nis, x, cov, nis, report, hold, tail);
}

}  // namespace birotor
