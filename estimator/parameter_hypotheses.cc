#include "estimator/parameter_hypotheses.h"

#include <algorithm>
#include <cmath>

namespace birotor {
namespace {

constexpr double kMinScaleStd = 1e-9;  // below the EKF's variance floor of r_m (1e-12) [1]

}  // namespace

double ChangedParameterProbability(double scale, double scale_std, double prior_std, double prior_probability) {
  if (prior_probability >= 1.0) return 1.0;
  const double s = std::max(scale_std, kMinScaleStd);
  const double z = (scale - 1.0) / s;
  // log of B01 (1 - p) / p; exp overflows to inf for a huge one: P(H1) 0.
  const double log_odds_h0 =
      std::log(prior_std / s) - 0.5 * z * z + std::log((1.0 - prior_probability) / prior_probability);
  return 1.0 / (1.0 + std::exp(log_odds_h0));
}

HypothesesAverage AverageOverHypotheses(double value, double variance, double covariance_with_scale, double scale,
                                        double scale_variance, double change_probability) {
  double value_h0 = value, variance_h0 = variance;
  if (scale_variance > 0.0) {
    const double gain = covariance_with_scale / scale_variance;
    value_h0 = value + gain * (1.0 - scale);
    variance_h0 = std::max(variance - gain * covariance_with_scale, 0.0);
  }
  const double w1 = change_probability, w0 = 1.0 - change_probability;
  const double spread = value_h0 - value;
  HypothesesAverage out;
  out.value = w0 * value_h0 + w1 * value;
  out.variance = w0 * variance_h0 + w1 * variance + w0 * w1 * spread * spread;
  return out;
}

}  // namespace birotor
