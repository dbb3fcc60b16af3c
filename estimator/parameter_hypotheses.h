// A vehicle parameter the file gives and the filter may learn, as two
// nested hypotheses (issue 36, docs/mismatch.md "Learning the payload" and
// "Learning the tip mass"): H0 the file's value (r = 1 exactly, r the
// parameter over the file's) and H1 a changed one (r ~ N(1, s_prior^2)).
// The filter learns r under H1; H0's estimate is the same Gaussian
// conditioned on r = 1, and what is published is the Bayesian average over
// the two. Used for the body mass (payload) and the tip mass. Pure
// functions, no state; a few flops and one exp per call.
#pragma once

namespace birotor {

// P(H1 | data) from the filter's posterior under H1, r ~ N(scale, scale_std^2),
// by the Savage-Dickey ratio of the nested hypotheses:
//   B01 = N(1; scale, scale_std^2) / N(1; 1, prior_std^2)
//       = (prior_std / scale_std) exp(-(scale - 1)^2 / (2 scale_std^2)),
//   P(H1 | data) = 1 / (1 + B01 (1 - p) / p),  p = prior_probability = P(H1).
// Before any data (scale 1, scale_std = prior_std) it is p; data that pins r
// near 1 lowers it (B01 = prior_std / scale_std), data that pins it away from 1
// raises it towards 1. prior_probability in (0, 1]; scale_std > 0 [1].
double ChangedParameterProbability(double scale, double scale_std, double prior_std, double prior_probability);

// A scalar of the filter (a force [N], a thrust scale [1], r itself) under both hypotheses.
struct HypothesesAverage {
  double value = 0;     // w0 x0 + w1 x
  double variance = 0;  // w0 var0 + w1 var + w0 w1 (x0 - x)^2
};

// The scalar x with variance var and covariance c with r under H1 (the
// filter's x, P), r ~ N(scale, scale_variance). Under H0 (r = 1, the Gaussian
// conditioned on it):
//   x0 = x + c (1 - scale) / scale_variance,  var0 = var - c^2 / scale_variance;
// averaged with w1 = change_probability, w0 = 1 - w1. scale_variance 0 (r
// not learned, or frozen): c is 0 as well and x0 = x, var0 = var.
HypothesesAverage AverageOverHypotheses(double value, double variance, double covariance_with_scale, double scale,
                                        double scale_variance, double change_probability);

}  // namespace birotor
