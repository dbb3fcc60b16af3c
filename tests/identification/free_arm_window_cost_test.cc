// FreeArmWindowCost: residuals and Jacobian of the forward sensitivities
// against Ceres' dynamic autodiff of the same functor (the chain rule of
// both, equal to rounding) and against central differences.
#include "identification/free_arm_window_cost.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

namespace birotor {
namespace {

struct Window {
  std::vector<FreeArmWindowResidual::Sample> samples;
  FreeArmWindowResidual::Noise noise{2e-5, 0.005, 0.05, 3.0};
  FreeArmWindowResidual::Scales scales{2628.0, 0.25, 4.6e-5, 0.288};
  std::vector<std::vector<double>> blocks;  // k, d, c_T, m_p ratios, x_0, knots
};

// 60 samples at 1 kHz near hover of the reference vehicle, measurements
// scattered so that some whitened residuals lie beyond the Huber threshold.
Window MakeWindow(double knot_s) {
  std::mt19937 rng(26);
  std::normal_distribution<double> unit(0.0, 1.0);
  Window w;
  for (int j = 0; j < 60; ++j) {
    FreeArmWindowResidual::Sample s{};
    s.dt_s = 0.001;
    s.omega_rad_s[0] = 780.0 + 20.0 * std::sin(0.2 * j);
    s.omega_rad_s[1] = 775.0 - 15.0 * std::cos(0.15 * j);
    s.deflection_rad[0] = 8e-4 + 1e-4 * unit(rng);
    s.deflection_rad[1] = -8e-4 + 1e-4 * unit(rng);
    s.gyro_rad_s = j == 7 ? std::nan("") : 0.02 * unit(rng);  // one missing gyro sample
    s.accel_m_s2[0] = 0.1 * unit(rng);
    s.accel_m_s2[1] = 9.81 + 0.2 * unit(rng);
    w.samples.push_back(s);
  }
  w.samples.back().dt_s = 0.0;
  w.blocks = {{1.01}, {0.97}, {1.02}, {0.99}, {0.01, 8e-4, -8e-4, 0.05, -0.03}};
  const FreeArmWindowResidual probe(BirotorParams(), w.samples, w.noise, 1, w.scales, knot_s);
  std::vector<double> knots(probe.KnotBlockSize());
  for (double& k : knots) k = 0.01 * unit(rng);
  if (!knots.empty()) w.blocks.push_back(knots);
  return w;
}

struct Evaluation {
  std::vector<double> residuals;
  std::vector<std::vector<double>> jacobians;  // per block, row-major
};

Evaluation Evaluate(const ceres::CostFunction& cost, std::vector<std::vector<double>> blocks, bool with_jacobians) {
  Evaluation out;
  out.residuals.resize(cost.num_residuals());
  std::vector<const double*> parameters;
  std::vector<double*> jacobians;
  for (size_t b = 0; b < blocks.size(); ++b) {
    parameters.push_back(blocks[b].data());
    out.jacobians.emplace_back(blocks[b].size() * cost.num_residuals());
    jacobians.push_back(out.jacobians.back().data());
  }
  EXPECT_TRUE(cost.Evaluate(parameters.data(), out.residuals.data(), with_jacobians ? jacobians.data() : nullptr));
  return out;
}

void ExpectSameAsAutoDiff(double knot_s, int substeps) {
  const Window w = MakeWindow(knot_s);
  std::unique_ptr<ceres::CostFunction> cost(
      FreeArmWindowCost::Create(BirotorParams(), w.samples, w.noise, substeps, w.scales, knot_s));
  std::unique_ptr<ceres::CostFunction> autodiff(
      FreeArmWindowResidual::CreateAutoDiff(BirotorParams(), w.samples, w.noise, substeps, w.scales, knot_s));
  ASSERT_EQ(cost->parameter_block_sizes(), autodiff->parameter_block_sizes());
  ASSERT_EQ(cost->num_residuals(), autodiff->num_residuals());
  const Evaluation a = Evaluate(*cost, w.blocks, true);
  const Evaluation b = Evaluate(*autodiff, w.blocks, true);
  int beyond_huber = 0;
  for (size_t i = 0; i < a.residuals.size(); ++i) {
    EXPECT_NEAR(a.residuals[i], b.residuals[i], 1e-12 * (1.0 + std::abs(b.residuals[i])));
    beyond_huber += std::abs(b.residuals[i]) > 3.0;
  }
  EXPECT_GT(beyond_huber, 0);  // the Huber branch is exercised
  double largest = 0.0;
  for (size_t block = 0; block < a.jacobians.size(); ++block) {
    for (size_t i = 0; i < a.jacobians[block].size(); ++i) {
      largest = std::max(largest, std::abs(b.jacobians[block][i]));
      // Same chain rule in a different order: equal to rounding.
      EXPECT_NEAR(a.jacobians[block][i], b.jacobians[block][i], 1e-9 * (1.0 + std::abs(b.jacobians[block][i])))
          << "block " << block << " entry " << i;
    }
  }
  EXPECT_GT(largest, 1.0);
  // Without Jacobians: the functor's own residuals, in double.
  const Evaluation r = Evaluate(*cost, w.blocks, false);
  for (size_t i = 0; i < r.residuals.size(); ++i) {
    EXPECT_NEAR(r.residuals[i], a.residuals[i], 1e-12 * (1.0 + std::abs(a.residuals[i])));
  }
}

TEST(FreeArmWindowCostTest, JacobianEqualsTheAutoDiffWithKnots) { ExpectSameAsAutoDiff(0.01, 1); }

TEST(FreeArmWindowCostTest, JacobianEqualsTheAutoDiffWithoutKnotsAndWithSubsteps) { ExpectSameAsAutoDiff(0.0, 2); }

TEST(FreeArmWindowCostTest, JacobianMatchesCentralDifferences) {
  const Window w = MakeWindow(0.01);
  std::unique_ptr<ceres::CostFunction> cost(
      FreeArmWindowCost::Create(BirotorParams(), w.samples, w.noise, 1, w.scales, 0.01));
  const Evaluation at = Evaluate(*cost, w.blocks, true);
  for (size_t block = 0; block < w.blocks.size(); ++block) {
    const size_t size = w.blocks[block].size();
    for (size_t c = 0; c < size; ++c) {
      std::vector<std::vector<double>> plus = w.blocks, minus = w.blocks;
      const double h = 1e-7 * std::max(1.0, std::abs(w.blocks[block][c]));
      plus[block][c] += h;
      minus[block][c] -= h;
      const Evaluation p = Evaluate(*cost, plus, false), m = Evaluate(*cost, minus, false);
      for (size_t i = 0; i < at.residuals.size(); ++i) {
        const double numeric = (p.residuals[i] - m.residuals[i]) / (2.0 * h);
        const double analytic = at.jacobians[block][i * size + c];
        // Central differences: truncation and rounding of about 1e-6 relative.
        EXPECT_NEAR(analytic, numeric, 1e-5 * (1.0 + std::abs(analytic))) << "block " << block << " column " << c;
      }
    }
  }
}

TEST(FreeArmWindowCostTest, AWindowBeyondTheLargestFallsBackToTheAutoDiff) {
  const Window w = MakeWindow(0.001);  // 60 knots per rotor
  const FreeArmWindowResidual* functor = nullptr;
  std::unique_ptr<ceres::CostFunction> cost(
      FreeArmWindowCost::Create(BirotorParams(), w.samples, w.noise, 1, w.scales, 0.001, &functor));
  ASSERT_NE(functor, nullptr);
  EXPECT_GT(9 + functor->KnotBlockSize(), FreeArmWindowCost::kMaxParameters);
  EXPECT_EQ(dynamic_cast<FreeArmWindowCost*>(cost.get()), nullptr);
  EXPECT_EQ(cost->parameter_block_sizes().back(), functor->KnotBlockSize());
}

}  // namespace
}  // namespace birotor
