// The one fusion path of every filter (the EKF and the linear methods),
// generic over the state size N and the measurement size M: innovation, chi-
// square gate, the inflation policy after persistent rejection, the update
// with the Kalman gain or a fixed gain, the covariance in Joseph form, and the
// FusionReport of what happened. A measurement model only says h(x) and H at
// the prior (MeasurementLinearization) and its noise R; it is never mutated.
// Header-only and fixed-size: no allocation, no throw, no log.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <cstdint>
#include <limits>

#include "estimator/fusion_report.h"

namespace birotor {

// A measurement model linearised at the prior x: z ~ h(x) + H (x' - x).
template <int M, int N>
struct MeasurementLinearization {
  Eigen::Matrix<double, M, 1> predicted;  // h(x), in the measurement's unit
  Eigen::Matrix<double, M, N> jacobian;   // H [unit of z per unit of each state]
};

// The same linearisation on the leading K of the N states (H's first K
// columns), for a measurement that reads only those (H's other columns are
// zero) or a filter whose trailing N - K states have zero rows and columns in
// P (then no fusion can move them: their gain P H^T S^-1 is zero, and so are
// their rows and columns of the Joseph update). The fusion takes blocks of x
// and P in place (FuseMeasurement: trailing states H does not read are
// updated through their cross covariance).
template <int K, int M, int N>
MeasurementLinearization<M, K> LeadingStates(const MeasurementLinearization<M, N>& at) {
  static_assert(K <= N, "the leading states of the N");
  MeasurementLinearization<M, K> out;
  out.predicted = at.predicted;
  out.jacobian = at.jacobian.template leftCols<K>();
  return out;
}

// Innovation of one measurement: y = z - h(x), S = H P H^T + R, NIS = y^T S^-1 y.
template <int M, int N>
struct Innovation {
  Eigen::Matrix<double, M, N> h_p;  // H P, shared by S, the gain and the Joseph update
  Eigen::Matrix<double, M, 1> residual;
  Eigen::Matrix<double, M, M> covariance;
  Eigen::Matrix<double, M, M> covariance_inverse;
  double nis = 0;
};

// cov: an N x N matrix or a block of one (the leading states, in place).
template <int M, int N, typename Cov>
Innovation<M, N> ComputeInnovation(const MeasurementLinearization<M, N>& at, const Eigen::Matrix<double, M, M>& noise,
                                   const Eigen::MatrixBase<Cov>& cov, const Eigen::Matrix<double, M, 1>& z) {
  Innovation<M, N> out;
  out.residual = z - at.predicted;
  // lazyProduct: coefficient-based; at 11-14 states Eigen's default would take
  // its blocked GEMM path (packing dominates at this size).
  out.h_p.noalias() = at.jacobian.lazyProduct(cov);
  out.covariance.noalias() = out.h_p.lazyProduct(at.jacobian.transpose());
  out.covariance += noise;
  out.covariance_inverse = out.covariance.inverse();
  out.nis = out.residual.dot(out.covariance_inverse * out.residual);
  return out;
}

// How the Joseph update (JosephCovariance) applies its last two rank-m
// corrections, -(A H^T) K^T + K R K^T (A = (I - K H) P):
enum class JosephForm {
  kSeparate,  // two products of n^2 m, one per correction
  // One product, -(A H^T - K R) K^T: the same Joseph product (for any gain;
  // A H^T - K R is zero at the optimal gain up to round-off, and is then
  // formed before it meets K^T), at half the cost; different round-off.
  kCombined,
};

// Covariance update in Joseph form, for any gain K (optimal or not):
//   P+ = (I - K H) P (I - K H)^T + K R K^T.
// The factor (I - K H) is applied as two rank-m corrections, A = P - K (H P)
// and A (I - K H)^T = A - (A H^T) K^T, so the product costs O(n^2 m) instead
// of O(n^3); it is the same product as the dense form, not the expanded
// P - K S K^T (which only equals it at the optimal gain and loses the
// positive semi-definite structure to round-off). Not symmetrised here.
// h_p = H P, as the innovation computed it; form: see JosephForm.
template <int N, int M, typename Cov>
Eigen::Matrix<double, N, N> JosephCovariance(const Eigen::MatrixBase<Cov>& cov, const Eigen::Matrix<double, N, M>& gain,
                                             const Eigen::Matrix<double, M, N>& h_p,
                                             const Eigen::Matrix<double, M, N>& h_jacobian,
                                             const Eigen::Matrix<double, M, M>& noise,
                                             JosephForm form = JosephForm::kSeparate) {
  Eigen::Matrix<double, N, N> out = cov;
  out.noalias() -= gain.lazyProduct(h_p);  // A = (I - K H) P
  Eigen::Matrix<double, N, M> a_ht;
  a_ht.noalias() = out.lazyProduct(h_jacobian.transpose());
  Eigen::Matrix<double, N, M> k_r;
  k_r.noalias() = gain.lazyProduct(noise);
  if (form == JosephForm::kCombined) {
    a_ht -= k_r;
    out.noalias() -= a_ht.lazyProduct(gain.transpose());  // (I - K H) P (I - K H)^T + K R K^T
  } else {
    out.noalias() -= a_ht.lazyProduct(gain.transpose());  // (I - K H) P (I - K H)^T
    out.noalias() += k_r.lazyProduct(gain.transpose());   // + K R K^T
  }
  return out;
}

template <int N, int M>
Eigen::Matrix<double, N, N> JosephCovariance(const Eigen::Matrix<double, N, N>& cov,
                                             const Eigen::Matrix<double, N, M>& gain,
                                             const Eigen::Matrix<double, M, N>& h_jacobian,
                                             const Eigen::Matrix<double, M, M>& noise) {
  Eigen::Matrix<double, M, N> h_p;
  h_p.noalias() = h_jacobian.lazyProduct(cov);
  return JosephCovariance<N, M>(cov, gain, h_p, h_jacobian, noise);
}

// The trailing T states of a filter that the measurement does not read
// (H = [H_K, 0]): their gain K_t = (H_K P_Kt)^T S^-1 and their rows of the
// Joseph update, the blocks of the N = K + T state product with H's zero
// columns left out (A = P - K H P, P+ = A - (A H^T) K^T + K R K^T):
//   A_tK = P_tK - K_t (H P)_K,  A_tt = P_tt - K_t (H P)_t,
//   P+_tK = A_tK - (A_tK H_K^T) K_K^T + K_t R K_K^T  (P+_Kt its transpose),
//   P+_tt = A_tt - (A_tK H_K^T) K_t^T + K_t R K_t^T.
// The leading block is JosephCovariance on the K states (the same product:
// H's zero columns add nothing). O(T K M) on top of the K-state update
// instead of O((N^2 - K^2) M): a random-walk parameter that only another
// sensor reads costs this measurement next to nothing.
// consider_states: bit j set: trailing state j (index among all N) gets a
// zero gain row (a Schmidt consider state, see KalmanUpdate).
template <int K, int M, typename State, typename Cov>
void UpdateTrailingStates(const MeasurementLinearization<M, K>& at, const Eigen::Matrix<double, M, M>& noise,
                          const Innovation<M, K>& innovation, const Eigen::Matrix<double, K, M>& gain, State* x,
                          Cov* cov, JosephForm form = JosephForm::kSeparate, uint32_t consider_states = 0) {
  constexpr int T = State::RowsAtCompileTime - K;
  Eigen::Matrix<double, M, T> h_p_t;
  h_p_t.noalias() = at.jacobian.lazyProduct(cov->template topRightCorner<K, T>());
  Eigen::Matrix<double, T, M> gain_t;
  gain_t.noalias() = h_p_t.transpose().lazyProduct(innovation.covariance_inverse);
  for (int j = 0; j < T && (consider_states >> K) != 0; ++j) {
    if ((consider_states >> (K + j)) & 1u) gain_t.row(j).setZero();
  }
  x->template tail<T>().noalias() += gain_t.lazyProduct(innovation.residual);
  Eigen::Matrix<double, T, K> a_tk = cov->template bottomLeftCorner<T, K>();
  a_tk.noalias() -= gain_t.lazyProduct(innovation.h_p);
  Eigen::Matrix<double, T, T> a_tt = cov->template bottomRightCorner<T, T>();
  a_tt.noalias() -= gain_t.lazyProduct(h_p_t);
  Eigen::Matrix<double, T, M> a_ht;
  a_ht.noalias() = a_tk.lazyProduct(at.jacobian.transpose());
  Eigen::Matrix<double, T, M> k_r;
  k_r.noalias() = gain_t.lazyProduct(noise);
  if (form == JosephForm::kCombined) {
    a_ht -= k_r;
    a_tk.noalias() -= a_ht.lazyProduct(gain.transpose());
    a_tt.noalias() -= a_ht.lazyProduct(gain_t.transpose());
  } else {
    a_tk.noalias() -= a_ht.lazyProduct(gain.transpose());
    a_tk.noalias() += k_r.lazyProduct(gain.transpose());
    a_tt.noalias() -= a_ht.lazyProduct(gain_t.transpose());
    a_tt.noalias() += k_r.lazyProduct(gain_t.transpose());
  }
  cov->template bottomLeftCorner<T, K>() = a_tk;
  cov->template topRightCorner<K, T>() = a_tk.transpose();
  cov->template bottomRightCorner<T, T>() = a_tt;
}

// x += K y and P by JosephCovariance, all from the innovation's H P. The gain
// is the optimal K = P H^T S^-1 = (H P)^T S^-1 (P is symmetric), or
// *fixed_gain when given (an observer's gain by pole placement).
// x and cov: N-vector and N x N matrix, or blocks of them (in place), N >= K:
// the measurement reads the leading K states (at is on them, the innovation
// on P's leading K x K block); the trailing N - K states are updated through
// their cross covariance (UpdateTrailingStates; optimal gain only).
// form: how the Joseph update sums its corrections (JosephForm).
// consider_states: bit j set: state j (0 .. N-1) is not moved by the update.
// Its row of the gain is zero (a Schmidt consider state) and the Joseph form
// gives P for that gain: the state keeps its value and variance, its
// correlations follow the other states, and the others' variances stay
// honest about it. 0: none (N <= 32).
template <int M, int K, typename State, typename Cov>
void KalmanUpdate(const MeasurementLinearization<M, K>& at, const Eigen::Matrix<double, M, M>& noise,
                  const Innovation<M, K>& innovation, State* x, Cov* cov,
                  const Eigen::Matrix<double, K, M>* fixed_gain = nullptr, JosephForm form = JosephForm::kSeparate,
                  uint32_t consider_states = 0) {
  constexpr int N = State::RowsAtCompileTime;
  static_assert(N >= K && Cov::RowsAtCompileTime == N && Cov::ColsAtCompileTime == N, "x and P of the N >= K states");
  Eigen::Matrix<double, K, M> gain;
  if (fixed_gain != nullptr) {
    gain = *fixed_gain;
  } else {
    gain.noalias() = innovation.h_p.transpose().lazyProduct(innovation.covariance_inverse);
  }
  for (int j = 0; j < K && consider_states != 0; ++j) {
    if ((consider_states >> j) & 1u) gain.row(j).setZero();
  }
  if constexpr (N > K) {
    // Before the leading block changes: the trailing update reads P_tK and P_Kt.
    UpdateTrailingStates(at, noise, innovation, gain, x, cov, form, consider_states);
    auto x_lead = x->template head<K>();
    x_lead.noalias() += gain.lazyProduct(innovation.residual);
    auto cov_lead = cov->template topLeftCorner<K, K>();
    cov_lead = JosephCovariance<K, M>(cov_lead, gain, innovation.h_p, at.jacobian, noise, form);
  } else {
    x->noalias() += gain.lazyProduct(innovation.residual);
    *cov = JosephCovariance<N, M>(*cov, gain, innovation.h_p, at.jacobian, noise, form);
  }
}

// What one measurement is fused with: its stamp, source and gate.
struct FusionRequest {
  FusionSource source = FusionSource::kStrain;
  int64_t utime = 0;  // [us]
  // Chi-square gate on the NIS; +infinity fuses whatever is finite. A NaN
  // NIS (a NaN reading, a broken covariance) is always rejected.
  double gate_nis = std::numeric_limits<double>::infinity();
  JosephForm joseph = JosephForm::kSeparate;  // how the covariance update sums its corrections
  uint32_t consider_states = 0;               // bit j: state j is not moved by the update (KalmanUpdate)
};

// Computes the innovation of z, gates it and, when it passes, updates *x and
// *cov. Returns what happened, with the innovation in z's unit.
// *cov is P (a matrix, or a block of one: see LeadingStates) of N or more
// states; the measurement reads the leading N (see KalmanUpdate).
template <int M, int N, typename State, typename Cov>
FusionReport FuseMeasurement(const MeasurementLinearization<M, N>& at, const Eigen::Matrix<double, M, M>& noise,
                             const Eigen::Matrix<double, M, 1>& z, const FusionRequest& request, State* x, Cov* cov,
                             const Eigen::Matrix<double, N, M>* fixed_gain = nullptr) {
  static_assert(M <= kMaxMeasurementSize, "FusionReport holds at most kMaxMeasurementSize values");
  const Innovation<M, N> innovation = ComputeInnovation(at, noise, cov->template topLeftCorner<N, N>(), z);
  FusionReport report;
  report.source = request.source;
  report.utime = request.utime;
  report.size = M;
  report.innovation.template head<M>() = innovation.residual;
  report.innovation_variance.template head<M>() = innovation.covariance.diagonal();
  report.nis = innovation.nis;
  report.gate = request.gate_nis;
  if (!(innovation.nis <= request.gate_nis)) {  // a NaN NIS is rejected too
    report.outcome = FusionOutcome::kRejectedGate;
    return report;
  }
  KalmanUpdate(at, noise, innovation, x, cov, fixed_gain, request.joseph, request.consider_states);
  report.outcome = FusionOutcome::kFused;
  return report;
}

// FuseMeasurement without building a report, for a measurement of any size
// M (the N-arm filters, estimator/multi_arm_*.h, report only what their
// pipeline reads): the same innovation, gate and update (with
// *fixed_gain when given, as FuseMeasurement); returns the outcome and, when
// nis is not null, the NIS.
template <int M, int N, typename State, typename Cov>
FusionOutcome FuseMeasurementUnreported(const MeasurementLinearization<M, N>& at,
                                        const Eigen::Matrix<double, M, M>& noise, const Eigen::Matrix<double, M, 1>& z,
                                        double gate_nis, State* x, Cov* cov, double* nis = nullptr,
                                        const Eigen::Matrix<double, N, M>* fixed_gain = nullptr) {
  const Innovation<M, N> innovation = ComputeInnovation(at, noise, cov->template topLeftCorner<N, N>(), z);
  if (nis != nullptr) *nis = innovation.nis;
  if (!(innovation.nis <= gate_nis)) return FusionOutcome::kRejectedGate;  // a NaN NIS is rejected too
  KalmanUpdate(at, noise, innovation, x, cov, fixed_gain);
  return FusionOutcome::kFused;
}

// The policy against a persistent change (a lost propeller blade): after
// consecutive_limit measurements in a row rejected by the gate, the change is
// taken as real: the covariance is inflated (the method says how) and the
// measurement is fused without the gate (a NaN NIS is still rejected).
class GateWithInflation {
 public:
  explicit GateWithInflation(int consecutive_limit) : consecutive_limit_(consecutive_limit) {}
  void Reset() { consecutive_rejected_ = 0; }
  int consecutive_rejected() const { return consecutive_rejected_; }

  // inflate(cov) widens the covariance before the ungated fusion. The report
  // keeps request.gate_nis as its gate, and fused_after_inflation says how it
  // was fused.
  template <int M, int N, typename State, typename Cov, typename Inflate>
  FusionReport Fuse(const MeasurementLinearization<M, N>& at, const Eigen::Matrix<double, M, M>& noise,
                    const Eigen::Matrix<double, M, 1>& z, const FusionRequest& request, State* x, Cov* cov,
                    Inflate&& inflate, const Eigen::Matrix<double, N, M>* fixed_gain = nullptr) {
    FusionReport report = FuseMeasurement(at, noise, z, request, x, cov, fixed_gain);
    if (report.outcome == FusionOutcome::kFused) {
      consecutive_rejected_ = 0;
      return report;
    }
    if (++consecutive_rejected_ < consecutive_limit_) return report;
    inflate(cov);
    FusionRequest ungated = request;
    ungated.gate_nis = std::numeric_limits<double>::infinity();
    report = FuseMeasurement(at, noise, z, ungated, x, cov, fixed_gain);
    report.gate = request.gate_nis;
    report.fused_after_inflation = report.outcome == FusionOutcome::kFused;
    if (report.fused_after_inflation) consecutive_rejected_ = 0;
    return report;
  }

  // The same policy on FuseMeasurementUnreported (any M; *fixed_gain as
  // there): kFused also after an inflation (*fused_after_inflation says
  // which, when not null).
  template <int M, int N, typename State, typename Cov, typename Inflate>
  FusionOutcome FuseUnreported(const MeasurementLinearization<M, N>& at, const Eigen::Matrix<double, M, M>& noise,
                               const Eigen::Matrix<double, M, 1>& z, double gate_nis, State* x, Cov* cov,
                               Inflate&& inflate, bool* fused_after_inflation = nullptr,
                               const Eigen::Matrix<double, N, M>* fixed_gain = nullptr) {
    return FuseUnreportedWith(
        gate_nis,
        [&](double gate) { return FuseMeasurementUnreported(at, noise, z, gate, x, cov, nullptr, fixed_gain); }, cov,
        inflate, fused_after_inflation);
  }

  // The same policy for any fusion of the one measurement: fuse(gate) gates
  // at gate and fuses or rejects, as FuseMeasurementUnreported (the N-arm
  // EKF's grouped fusions, estimator/multi_arm_ekf_fusion.h).
  template <typename Fuse, typename Cov, typename Inflate>
  FusionOutcome FuseUnreportedWith(double gate_nis, Fuse&& fuse, Cov* cov, Inflate&& inflate,
                                   bool* fused_after_inflation = nullptr) {
    if (fused_after_inflation != nullptr) *fused_after_inflation = false;
    FusionOutcome outcome = fuse(gate_nis);
    if (outcome == FusionOutcome::kFused) {
      consecutive_rejected_ = 0;
      return outcome;
    }
    if (++consecutive_rejected_ < consecutive_limit_) return outcome;
    inflate(cov);
    outcome = fuse(std::numeric_limits<double>::infinity());
    if (outcome == FusionOutcome::kFused) {
      consecutive_rejected_ = 0;
      if (fused_after_inflation != nullptr) *fused_after_inflation = true;
    }
    return outcome;
  }

 private:
  int consecutive_limit_;
  int consecutive_rejected_ = 0;
};

}  // namespace birotor
