// Shared pieces of the identification fits: time alignment of sensor streams,
// splitting into contiguous windows, solving, residual statistics and
// one-sigma uncertainties from ceres::Covariance.
#pragma once

#include <ceres/problem.h>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "identification/identification_options.h"
#include "identification/identification_result.h"

namespace birotor {

// Linear interpolation of value(sample) at t_us over samples sorted by utime.
// False outside the data or across a gap longer than max_gap_us. *hint is a
// search start that only moves forward (call with increasing t_us).
template <class Sample, class Value>
bool InterpolateAt(const std::vector<Sample>& samples, int64_t t_us, int64_t max_gap_us, size_t* hint,
                   const Value& value, double* out) {
  size_t i = *hint;
  while (i + 1 < samples.size() && samples[i + 1].utime <= t_us) ++i;
  *hint = i;
  if (samples.empty() || t_us < samples[i].utime) return false;
  if (samples[i].utime == t_us) {
    *out = value(samples[i]);
    return true;
  }
  if (i + 1 >= samples.size()) return false;
  const int64_t gap = samples[i + 1].utime - samples[i].utime;
  if (gap > max_gap_us) return false;
  const double alpha = static_cast<double>(t_us - samples[i].utime) / static_cast<double>(gap);
  *out = value(samples[i]) + alpha * (value(samples[i + 1]) - value(samples[i]));
  return true;
}

// Index ranges [begin, end) of runs of valid samples (valid[i]) no longer than
// window_s, with no interval above max_gap_us; runs shorter than min_samples
// are dropped.
std::vector<std::pair<size_t, size_t>> ContiguousWindows(const std::vector<int64_t>& utime,
                                                         const std::vector<bool>& valid, double window_s,
                                                         int64_t max_gap_us, size_t min_samples);

// Median interval of a sorted time stamp list [us] (0 when fewer than two).
int64_t MedianIntervalUs(const std::vector<int64_t>& utime);

// Ceres solver options shared by the fits (trust region, sparse Schur); the
// solve stops when an iteration changes the cost by less than
// function_tolerance times the cost.
// With `at` and options.progress, the progress is reported at every iteration.
void SolveProblem(const IdentificationOptions& options, ceres::Problem* problem, double function_tolerance = 1e-10,
                  const FitProgress* at = nullptr);

// Reports `at` through options.progress when there is one.
void ReportProgress(const IdentificationOptions& options, const FitProgress& at);

// Residual statistics of the given residual blocks after the fit, without the
// robust loss. sequence_length groups consecutive residuals of one channel into
// time series (stride = channels interleaved per sample) for the correlation.
struct ResidualStatistics {
  int count = 0;
  double rms_whitened = 0.0;      // [sigma]
  double robust_scale = 1.0;      // 1.4826 median |r| [sigma]
  double correlation_time = 1.0;  // 1 + 2 sum of autocorrelations [samples]
};
ResidualStatistics ComputeResidualStatistics(ceres::Problem* problem, const std::vector<ceres::ResidualBlockId>& blocks,
                                             int stride, int channel);

// Variance inflation that makes the covariance honest when the residuals are
// larger than their assumed sigma or correlated in time:
// max(1, robust_scale^2, rms_whitened^2) * max(1, correlation_time).
// A model that does not fit the data (RMS well above one) widens every sigma.
double VarianceInflation(const ResidualStatistics& stats);

// Correlation matrix of the listed one-scalar parameter blocks (none of them
// constant), from ceres::Covariance; empty when the information matrix is
// singular.
std::vector<std::vector<double>> ComputeBlockCorrelations(ceres::Problem* problem, const std::vector<double*>& blocks,
                                                          int num_threads);

// The parameter pairs the data cannot separate (|rho| above `threshold`)
// and the combination that is determined: the ratio a / b for rho > 0, the
// product a b for rho < 0, with its relative one sigma
//   var(ln a -+ ln b) = (sa/a)^2 + (sb/b)^2 -+ 2 rho (sa/a)(sb/b).
// names, values, sigmas: per block, in the order of `correlation`.
std::vector<DeterminedCombination> DescribeCorrelations(const std::vector<std::vector<double>>& correlation,
                                                        const std::vector<std::string>& names,
                                                        const std::vector<double>& values,
                                                        const std::vector<double>& sigmas, double threshold);

// One-sigma of the listed one-scalar parameter blocks (ratios to their
// scales), from ceres::Covariance (sparse QR). A block along which the
// information matrix is singular gets determined = false; the others are
// computed with it held. sigma is multiplied by sqrt(variance_inflation).
// *covariance (optional): the un-inflated covariance of the blocks from the
// same factorization (rows of blocks held or constant are 0; empty when
// the information matrix is singular).
struct BlockSigma {
  bool determined = false;
  double sigma = 0.0;  // in units of the block value
};
// Whether a fit's one sigma determines value: a finite sigma (the block's
// BlockSigma::determined) at most max_relative_sigma of |value| and never
// above 100 % (a value zero within one sigma is not determined, whatever
// max_relative_sigma is set to; the report says so, and --update-params
// writes only what this says).
bool SigmaDetermines(bool sigma_determined, double value, double sigma, double max_relative_sigma);

std::vector<BlockSigma> ComputeBlockSigmas(ceres::Problem* problem, const std::vector<double*>& blocks,
                                           double variance_inflation, int num_threads,
                                           Eigen::MatrixXd* covariance = nullptr);

// Cluster-robust ("sandwich") one-sigma of the listed one-scalar parameter
// blocks (the shared parameters) when the residual blocks `clusters` are
// statistically independent of each other (flight windows 1.5 s apart)
// but their residuals are not white inside a block (unmodelled turbulence):
//   V = C (G / (G - p)) sum_w g_w g_w^T C,
// C the covariance of the blocks from the information matrix (every other
// parameter profiled out; `covariance` of ComputeBlockSigmas), g_w the gradient of cluster w's cost with
// respect to the blocks at the optimum (the profiled score: the window's own
// parameters are at their optimum), G clusters, p blocks. Constant blocks
// get 0; an empty vector when C is empty or G <= p.
std::vector<double> ComputeClusterRobustSigmas(ceres::Problem* problem, const std::vector<double*>& blocks,
                                               const Eigen::MatrixXd& covariance,
                                               const std::vector<ceres::ResidualBlockId>& clusters, int num_threads);

}  // namespace birotor
