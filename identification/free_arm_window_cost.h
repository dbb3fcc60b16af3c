// The cost function of one free-flight window (FreeArmWindowResidual) with
// its Jacobian from forward sensitivities: the state x and S = dx / dtheta
// over every parameter of the block are integrated together by the one RK4
// step of model/rk4.h, each stage linearised by a 10-wide Jet over (x, k, d,
// m_p, f1, f2) only. The numbers are those of Ceres' forward-mode autodiff of
// the functor (the same chain rule, rounding aside) at about a twentieth of
// the cost: the autodiff carried every parameter of the window through every
// operation of the integration, in two 12-wide passes.
#pragma once

#include <ceres/cost_function.h>

#include <memory>
#include <vector>

#include "identification/free_arm_residual.h"

namespace birotor {

class FreeArmWindowCost : public ceres::CostFunction {
 public:
  // Most parameters of a window (4 ratios, x_0, knots of both rotors): 27
  // knots per rotor, a 1.3 s window at 0.05 s knots. A larger window falls
  // back to FreeArmWindowResidual::CreateAutoDiff.
  static constexpr int kMaxParameters = 4 + kFreeArmStateSize + 2 * 27;

  // Same arguments and parameter blocks as FreeArmWindowResidual::CreateAutoDiff;
  // *functor (optional) keeps a view of the functor, owned by the cost function.
  static ceres::CostFunction* Create(const BirotorParams& known, std::vector<FreeArmWindowResidual::Sample> samples,
                                     const FreeArmWindowResidual::Noise& noise, int substeps,
                                     const FreeArmWindowResidual::Scales& scales, double turbulence_knot_s,
                                     const FreeArmWindowResidual** functor = nullptr);

  explicit FreeArmWindowCost(std::unique_ptr<const FreeArmWindowResidual> residual);

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  std::unique_ptr<const FreeArmWindowResidual> residual_;
};

}  // namespace birotor
