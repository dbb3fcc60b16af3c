#include "estimator/strain_scale_attribution.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace birotor {
namespace {

// The evidence's direction A (a, d, b) per unit of each change's parameter,
// and that parameter's prior sigma.
struct Hypothesis {
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  double prior_std = 0.0;
};

Hypothesis HypothesisOf(ScaleChange change, const ScaleAttributionOptions& o) {
  switch (change) {
    case ScaleChange::kNone:
      return Hypothesis();
    case ScaleChange::kStiffness:  // k = k_file e^kappa: a = -kappa, b = kappa / 2
      return {Eigen::Vector3d(-1.0, 0.0, 0.5), o.stiffness_prior_std};
    case ScaleChange::kTipMass:  // m_p = m_p,file e^mu: b = S mu
      return {Eigen::Vector3d(0.0, 0.0, o.tip_mass_mode_slope), o.tip_mass_prior_std};
    case ScaleChange::kGauge1:  // s_1 = s_1,file e^sigma: a = sigma / 2, d = sigma
      return {Eigen::Vector3d(0.5, 1.0, 0.0), o.gauge_scale_prior_std};
    case ScaleChange::kGauge2:  // s_2 = s_2,file e^sigma: a = sigma / 2, d = -sigma
      return {Eigen::Vector3d(0.5, -1.0, 0.0), o.gauge_scale_prior_std};
    case ScaleChange::kCommonScale:  // M = M_file e^beta (or both gauges alike): a = beta
      return {Eigen::Vector3d(1.0, 0.0, 0.0), o.common_scale_prior_std};
  }
  return Hypothesis();
}

}  // namespace

ScaleAttribution AttributeScales(const ScaleEvidence& e, const ScaleAttributionOptions& o) {
  const Eigen::Vector3d y(0.5 * (e.log_scale[0] + e.log_scale[1]), e.log_scale[0] - e.log_scale[1], e.mode_shift);
  // R: a and d from the two independent ln g_i, b alone; plus the tolerance.
  const double v1 = std::max(e.log_scale_var[0], 0.0), v2 = std::max(e.log_scale_var[1], 0.0);
  const double t2 = o.tolerance * o.tolerance;
  Eigen::Matrix3d r = Eigen::Matrix3d::Zero();
  r(0, 0) = 0.25 * (v1 + v2) + t2;
  r(0, 1) = r(1, 0) = 0.5 * (v1 - v2);
  r(1, 1) = v1 + v2 + t2;
  r(2, 2) = std::max(e.mode_shift_var, 0.0) + t2;

  // The file's vehicle or one change (prior probability p each).
  ScaleAttribution out;
  out.best_distance2 = 1e300;
  std::array<double, kScaleChangeCount> log_posterior{};
  for (int k = 0; k < kScaleChangeCount; ++k) {
    const ScaleChange change = static_cast<ScaleChange>(k);
    const Hypothesis h = HypothesisOf(change, o);
    const Eigen::Matrix3d c = r + h.prior_std * h.prior_std * h.direction * h.direction.transpose();
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(c);
    const double distance2 = y.dot(ldlt.solve(y));
    const double log_det = ldlt.vectorD().array().log().sum();
    const double prior =
        change == ScaleChange::kNone ? 1.0 - (kScaleChangeCount - 1) * o.change_probability : o.change_probability;
    log_posterior[static_cast<size_t>(k)] = std::log(std::max(prior, 1e-12)) - 0.5 * (distance2 + log_det);
    out.best_distance2 = std::min(out.best_distance2, distance2);
  }
  const double top = *std::max_element(log_posterior.begin(), log_posterior.end());
  double sum = 0.0;
  for (int k = 0; k < kScaleChangeCount; ++k) {
    out.weight[static_cast<size_t>(k)] = std::exp(log_posterior[static_cast<size_t>(k)] - top);
    sum += out.weight[static_cast<size_t>(k)];
  }
  for (double& w : out.weight) w /= sum;
  out.explained = out.best_distance2 <= o.explained_distance2;
  return out;
}

}  // namespace birotor
