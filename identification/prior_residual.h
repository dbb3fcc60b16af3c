// Ceres residual of an outside fact about one parameter: a value known with
// a one-sigma uncertainty (a weighed tip mass, a gauge's factory scale).
#pragma once

#include <ceres/autodiff_cost_function.h>

namespace birotor {

// r = (theta - theta_prior) / sigma_prior                          [1, whitened]
// in the parameter's own unit (a ratio to its scale or a plain value).
struct PriorResidual {
  PriorResidual(double prior, double sigma) : prior_(prior), inv_sigma_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* theta, T* residual) const {
    residual[0] = (theta[0] - prior_) * inv_sigma_;
    return true;
  }

  static ceres::CostFunction* Create(double prior, double sigma) {
    return new ceres::AutoDiffCostFunction<PriorResidual, 1, 1>(new PriorResidual(prior, sigma));
  }

  const double prior_;
  const double inv_sigma_;
};

}  // namespace birotor
