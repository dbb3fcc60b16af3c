#include "identification/fit_support.h"

#include <ceres/covariance.h>
#include <ceres/solver.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>

namespace birotor {

std::vector<std::pair<size_t, size_t>> ContiguousWindows(const std::vector<int64_t>& utime,
                                                         const std::vector<bool>& valid, double window_s,
                                                         int64_t max_gap_us, size_t min_samples) {
  std::vector<std::pair<size_t, size_t>> windows;
  const int64_t window_us = static_cast<int64_t>(std::llround(window_s * 1e6));
  size_t begin = 0;
  auto close = [&](size_t end) {
    if (end > begin && end - begin >= min_samples) windows.emplace_back(begin, end);
  };
  while (begin < utime.size() && !valid[begin]) ++begin;
  for (size_t i = begin + 1; i <= utime.size(); ++i) {
    if (begin >= utime.size()) break;
    const bool end_of_data = i == utime.size();
    const bool breaks = end_of_data || !valid[i] || utime[i] - utime[i - 1] > max_gap_us ||
                        utime[i] - utime[i - 1] <= 0 || utime[i] - utime[begin] >= window_us;
    if (!breaks) continue;
    close(i);
    begin = i;
    while (begin < utime.size() && !valid[begin]) ++begin;
    i = begin;
  }
  return windows;
}

int64_t MedianIntervalUs(const std::vector<int64_t>& utime) {
  if (utime.size() < 2) return 0;
  std::vector<int64_t> dt(utime.size() - 1);
  for (size_t i = 1; i < utime.size(); ++i) dt[i - 1] = utime[i] - utime[i - 1];
  std::nth_element(dt.begin(), dt.begin() + dt.size() / 2, dt.end());
  return dt[dt.size() / 2];
}

namespace {

// Reports each solver iteration through options.progress.
class ProgressCallback : public ceres::IterationCallback {
 public:
  ProgressCallback(const IdentificationOptions& options, const FitProgress& at) : options_(options), at_(at) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    at_.iteration = summary.iteration;
    options_.progress(at_);
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const IdentificationOptions& options_;
  FitProgress at_;
};

}  // namespace

void ReportProgress(const IdentificationOptions& options, const FitProgress& at) {
  if (options.progress) options.progress(at);
}

void SolveProblem(const IdentificationOptions& options, ceres::Problem* problem, double function_tolerance,
                  const FitProgress* at) {
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_SCHUR;
  solver.max_num_iterations = options.max_iterations;
  solver.num_threads = options.num_threads;
  solver.function_tolerance = function_tolerance;
  solver.parameter_tolerance = 1e-10;
  solver.logging_type = ceres::SILENT;
  std::unique_ptr<ProgressCallback> callback;
  if (at != nullptr && options.progress) {
    ReportProgress(options, *at);
    callback = std::make_unique<ProgressCallback>(options, *at);
    solver.callbacks.push_back(callback.get());
  }
  ceres::Solver::Summary summary;
  ceres::Solve(solver, problem, &summary);
}

ResidualStatistics ComputeResidualStatistics(ceres::Problem* problem, const std::vector<ceres::ResidualBlockId>& blocks,
                                             int stride, int channel) {
  ResidualStatistics stats;
  if (blocks.empty()) return stats;
  std::vector<double> abs_values;
  double sum_sq = 0.0;
  // Autocorrelation from per-block series, residuals clipped at 5 sigma so a
  // spike does not dominate.
  constexpr int kMaxLag = 200;
  std::vector<double> lag_sum(kMaxLag + 1, 0.0);
  std::vector<double> lag_count(kMaxLag + 1, 0.0);
  ceres::Problem::EvaluateOptions evaluate;
  evaluate.apply_loss_function = false;
  std::vector<double> residuals;
  for (const ceres::ResidualBlockId id : blocks) {
    evaluate.residual_blocks = {id};
    double cost = 0.0;
    problem->Evaluate(evaluate, &cost, &residuals, nullptr, nullptr);
    std::vector<double> series;
    for (size_t i = channel; i < residuals.size(); i += stride) {
      const double r = residuals[i];
      if (r == 0.0) continue;  // missing measurement
      series.push_back(std::clamp(r, -5.0, 5.0));
      abs_values.push_back(std::abs(r));
      sum_sq += r * r;
    }
    for (int lag = 0; lag <= kMaxLag && lag < static_cast<int>(series.size()); ++lag) {
      for (size_t i = lag; i < series.size(); ++i) lag_sum[lag] += series[i] * series[i - lag];
      lag_count[lag] += static_cast<double>(series.size() - lag);
    }
  }
  stats.count = static_cast<int>(abs_values.size());
  if (stats.count == 0) return stats;
  stats.rms_whitened = std::sqrt(sum_sq / stats.count);
  std::nth_element(abs_values.begin(), abs_values.begin() + abs_values.size() / 2, abs_values.end());
  stats.robust_scale = 1.4826 * abs_values[abs_values.size() / 2];
  if (lag_count[0] > 0 && lag_sum[0] > 0) {
    const double c0 = lag_sum[0] / lag_count[0];
    double tau = 1.0;
    for (int lag = 1; lag <= kMaxLag && lag_count[lag] > 0; ++lag) {
      const double rho = lag_sum[lag] / lag_count[lag] / c0;
      if (rho <= 0.0) break;
      tau += 2.0 * rho;
    }
    stats.correlation_time = tau;
  }
  return stats;
}

namespace {

// Sparse QR: robust to the near-singular blocks ComputeBlockSigmas probes.
ceres::Covariance::Options CovarianceOptions(int num_threads) {
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::SPARSE_QR;
  options.num_threads = num_threads;
  return options;
}

}  // namespace

double VarianceInflation(const ResidualStatistics& stats) {
  const double scale_sq =
      std::max({1.0, stats.robust_scale * stats.robust_scale, stats.rms_whitened * stats.rms_whitened});
  return scale_sq * std::max(1.0, stats.correlation_time);
}

std::vector<std::vector<double>> ComputeBlockCorrelations(ceres::Problem* problem, const std::vector<double*>& blocks,
                                                          int num_threads) {
  ceres::Covariance covariance(CovarianceOptions(num_threads));
  std::vector<std::pair<const double*, const double*>> pairs;
  for (size_t i = 0; i < blocks.size(); ++i) {
    for (size_t j = i; j < blocks.size(); ++j) pairs.emplace_back(blocks[i], blocks[j]);
  }
  if (blocks.empty() || !covariance.Compute(pairs, problem)) return {};
  const size_t n = blocks.size();
  std::vector<std::vector<double>> c(n, std::vector<double>(n, 0.0));
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i; j < n; ++j) {
      covariance.GetCovarianceBlock(blocks[i], blocks[j], &c[i][j]);
      c[j][i] = c[i][j];
    }
  }
  std::vector<std::vector<double>> rho(n, std::vector<double>(n, 0.0));
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < n; ++j) {
      const double denominator = std::sqrt(std::max(0.0, c[i][i]) * std::max(0.0, c[j][j]));
      rho[i][j] = denominator > 0.0 ? c[i][j] / denominator : (i == j ? 1.0 : 0.0);
    }
  }
  return rho;
}

std::vector<DeterminedCombination> DescribeCorrelations(const std::vector<std::vector<double>>& correlation,
                                                        const std::vector<std::string>& names,
                                                        const std::vector<double>& values,
                                                        const std::vector<double>& sigmas, double threshold) {
  std::vector<DeterminedCombination> combinations;
  for (size_t i = 0; i < correlation.size(); ++i) {
    for (size_t j = i + 1; j < correlation.size(); ++j) {
      const double rho = correlation[i][j];
      if (std::abs(rho) < threshold || values[i] == 0.0 || values[j] == 0.0) continue;
      const double ra = sigmas[i] / std::abs(values[i]), rb = sigmas[j] / std::abs(values[j]);
      const double sign = rho > 0.0 ? -1.0 : 1.0;  // ratio for rho > 0, product for rho < 0
      DeterminedCombination c;
      c.kind = rho > 0.0 ? CombinationKind::kRatio : CombinationKind::kProduct;
      c.a = names[i];
      c.b = names[j];
      c.correlation = rho;
      c.relative_sigma = std::sqrt(std::max(0.0, ra * ra + rb * rb + 2.0 * sign * rho * ra * rb));
      combinations.push_back(c);
    }
  }
  return combinations;
}

namespace {

bool TryCovariance(ceres::Problem* problem, const std::vector<double*>& blocks, const std::vector<bool>& use,
                   int num_threads, std::vector<double>* variances, Eigen::MatrixXd* full = nullptr) {
  ceres::Covariance covariance(CovarianceOptions(num_threads));
  std::vector<std::pair<const double*, const double*>> pairs;
  for (size_t i = 0; i < blocks.size(); ++i) {
    for (size_t j = i; j < blocks.size() && use[i]; ++j) {
      if (use[j] && (j == i || full != nullptr)) pairs.emplace_back(blocks[i], blocks[j]);
    }
  }
  if (pairs.empty()) return true;
  if (!covariance.Compute(pairs, problem)) return false;
  if (full != nullptr)
    full->setZero(static_cast<Eigen::Index>(blocks.size()), static_cast<Eigen::Index>(blocks.size()));
  for (size_t i = 0; i < blocks.size(); ++i) {
    for (size_t j = i; j < blocks.size() && use[i]; ++j) {
      if (!use[j] || (j != i && full == nullptr)) continue;
      double v = 0.0;
      covariance.GetCovarianceBlock(blocks[i], blocks[j], &v);
      if (i == j) (*variances)[i] = v;
      if (full != nullptr) (*full)(i, j) = (*full)(j, i) = v;
    }
  }
  return true;
}

}  // namespace

bool SigmaDetermines(bool sigma_determined, double value, double sigma, double max_relative_sigma) {
  return sigma_determined && std::isfinite(value) && std::isfinite(sigma) &&
         sigma <= std::min(max_relative_sigma, 1.0) * std::abs(value);
}

std::vector<BlockSigma> ComputeBlockSigmas(ceres::Problem* problem, const std::vector<double*>& blocks,
                                           double variance_inflation, int num_threads, Eigen::MatrixXd* covariance) {
  std::vector<BlockSigma> out(blocks.size());
  std::vector<double> variances(blocks.size(), 0.0);
  std::vector<bool> use(blocks.size(), true);
  for (size_t i = 0; i < blocks.size(); ++i) use[i] = !problem->IsParameterBlockConstant(blocks[i]);
  bool computed = TryCovariance(problem, blocks, use, num_threads, &variances, covariance);
  if (!computed && covariance != nullptr) covariance->resize(0, 0);
  // Singular: find the blocks whose removal makes it regular, one at a time.
  for (size_t i = 0; !computed && i < blocks.size(); ++i) {
    if (!use[i]) continue;
    problem->SetParameterBlockConstant(blocks[i]);
    std::vector<bool> others = use;
    others[i] = false;
    if (TryCovariance(problem, blocks, others, num_threads, &variances)) {
      use = others;
      computed = true;
    }
    problem->SetParameterBlockVariable(blocks[i]);
  }
  if (!computed) return out;  // nothing determined
  for (size_t i = 0; i < blocks.size(); ++i) {
    out[i].determined = use[i];
    out[i].sigma = use[i] ? std::sqrt(std::max(0.0, variances[i]) * variance_inflation) : 0.0;
  }
  return out;
}

std::vector<double> ComputeClusterRobustSigmas(ceres::Problem* problem, const std::vector<double*>& blocks,
                                               const Eigen::MatrixXd& covariance,
                                               const std::vector<ceres::ResidualBlockId>& clusters, int num_threads) {
  std::vector<double*> active;
  std::vector<Eigen::Index> index;
  for (size_t i = 0; i < blocks.size() && covariance.rows() == static_cast<Eigen::Index>(blocks.size()); ++i) {
    if (problem->IsParameterBlockConstant(blocks[i]) || covariance(i, i) <= 0.0) continue;
    active.push_back(blocks[i]);
    index.push_back(static_cast<Eigen::Index>(i));
  }
  const size_t p = active.size();
  if (p == 0 || clusters.size() <= p) return {};
  Eigen::MatrixXd c(p, p);
  for (size_t i = 0; i < p; ++i) {
    for (size_t j = 0; j < p; ++j) c(i, j) = covariance(index[i], index[j]);
  }
  Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(p, p);
  ceres::Problem::EvaluateOptions evaluate;
  evaluate.parameter_blocks = active;
  evaluate.num_threads = num_threads;
  std::vector<double> gradient;
  for (const ceres::ResidualBlockId id : clusters) {
    evaluate.residual_blocks = {id};
    double cost = 0.0;
    if (!problem->Evaluate(evaluate, &cost, nullptr, &gradient, nullptr)) return {};
    const Eigen::Map<const Eigen::VectorXd> g(gradient.data(), static_cast<Eigen::Index>(p));
    meat += g * g.transpose();
  }
  const double clusters_n = static_cast<double>(clusters.size());
  const Eigen::MatrixXd v = c * meat * c * (clusters_n / (clusters_n - static_cast<double>(p)));
  std::vector<double> sigma(blocks.size(), 0.0);
  for (size_t i = 0; i < p; ++i) sigma[index[i]] = std::sqrt(std::max(0.0, v(i, i)));
  return sigma;
}

}  // namespace birotor
