// The N-arm EKF's grouped-Joseph fusions (estimator/multi_arm_ekf_fusion.h)
// against FuseMeasurementUnreported (estimator/kalman_fusion.h) on random
// problems: the same outcome and NIS, x and P equal to rounding (the Joseph
// terms are grouped, so not bit for bit), P+ exactly symmetric, for a dense H
// with leading zero columns (FuseSymmetricUnreported), for unit rows and for
// sums of two unit rows (the strain's b_i + e_i), each with a masked zero row
// (FuseOnesRowsUnreported), and the same gate rejection.
#include "estimator/multi_arm_ekf_fusion.h"

#include <gtest/gtest.h>

#include <random>

#include "estimator/kalman_fusion.h"

namespace birotor {
namespace {

constexpr int kN = 7, kM = 3;
using State = Eigen::Matrix<double, kN, 1>;
using Cov = Eigen::Matrix<double, kN, kN>;
using Linearization = MeasurementLinearization<kM, kN>;

struct Problem {
  Linearization at;
  Eigen::Matrix<double, kM, kM> noise;
  Eigen::Matrix<double, kM, 1> z;
  State x;
  Cov p;
};

enum class Rows { kDense, kUnit, kSumsOfTwo };
constexpr int kZeroColumns = 2;  // of the dense H

// A symmetric positive definite P, a diagonal R, z at innovation_scale from
// h(x); H dense but for its first kZeroColumns, or unit rows reading states 5,
// 1 and none (a masked row), or rows reading 5 + 2, 1 + 4 and none.
Problem RandomProblem(std::mt19937* rng, Rows rows, double innovation_scale) {
  std::normal_distribution<double> g(0.0, 1.0);
  Problem out;
  out.at.jacobian.setZero();
  for (int r = 0; r < kM; ++r) {
    out.at.predicted(r) = g(*rng);
    out.z(r) = out.at.predicted(r) + innovation_scale * g(*rng);
    for (int c = kZeroColumns; c < kN && rows == Rows::kDense; ++c) out.at.jacobian(r, c) = g(*rng);
  }
  if (rows != Rows::kDense) {
    out.at.jacobian(0, 5) = 1.0;
    out.at.jacobian(1, 1) = 1.0;  // row 2 stays zero: not measured
  }
  if (rows == Rows::kSumsOfTwo) {
    out.at.jacobian(0, 2) = 1.0;
    out.at.jacobian(1, 4) = 1.0;
  }
  out.noise = Eigen::Matrix<double, kM, kM>::Zero();
  for (int r = 0; r < kM; ++r) out.noise(r, r) = 0.05 + 0.1 * std::abs(g(*rng));
  Cov a;
  for (int r = 0; r < kN; ++r) {
    out.x(r) = g(*rng);
    for (int c = 0; c < kN; ++c) a(r, c) = g(*rng);
  }
  const Cov p = a * a.transpose() + Cov::Identity();
  out.p = 0.5 * (p + p.transpose());  // exactly symmetric, as the filter's P
  return out;
}

// Both fusions on copies of the problem; the reference is FuseMeasurementUnreported.
template <typename Fuse>
void ExpectSameAsReference(const Problem& problem, double gate_nis, Fuse&& fuse) {
  State x_ref = problem.x, x = problem.x;
  Cov p_ref = problem.p, p = problem.p;
  double nis_ref = 0, nis = 0;
  const FusionOutcome ref =
      FuseMeasurementUnreported(problem.at, problem.noise, problem.z, gate_nis, &x_ref, &p_ref, &nis_ref);
  const FusionOutcome got = fuse(problem, gate_nis, &x, &p, &nis);
  ASSERT_EQ(got, ref);
  EXPECT_NEAR(nis, nis_ref, 1e-12 * (1.0 + nis_ref));
  EXPECT_LT((x - x_ref).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + x_ref.cwiseAbs().maxCoeff()));
  EXPECT_LT((p - p_ref).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + p_ref.cwiseAbs().maxCoeff()));
  EXPECT_EQ((p - p.transpose()).cwiseAbs().maxCoeff(), 0.0);  // computed once a pair
}

TEST(MultiArmEkfFusionTest, DenseRowsMatchTheReference) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const double gate = trial % 4 == 0 ? 0.5 : 1e9;  // every fourth one mostly rejected
    ExpectSameAsReference(RandomProblem(&rng, Rows::kDense, 1.0), gate,
                          [](const Problem& p, double g, State* x, Cov* cov, double* nis) {
                            return FuseSymmetricUnreported<kZeroColumns>(p.at, p.noise, p.z, g, x, cov, nis);
                          });
  }
}

TEST(MultiArmEkfFusionTest, UnitRowsWithAMaskedRowMatchTheReference) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const double gate = trial % 4 == 0 ? 0.5 : 1e9;
    ExpectSameAsReference(RandomProblem(&rng, Rows::kUnit, 1.0), gate,
                          [](const Problem& p, double g, State* x, Cov* cov, double* nis) {
                            return FuseOnesRowsUnreported(p.at, p.noise, p.z, g, x, cov, nis);
                          });
  }
}

TEST(MultiArmEkfFusionTest, SumsOfTwoUnitRowsWithAMaskedRowMatchTheReference) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const double gate = trial % 4 == 0 ? 0.5 : 1e9;
    ExpectSameAsReference(RandomProblem(&rng, Rows::kSumsOfTwo, 1.0), gate,
                          [](const Problem& p, double g, State* x, Cov* cov, double* nis) {
                            return FuseOnesRowsUnreported(p.at, p.noise, p.z, g, x, cov, nis);
                          });
  }
}

TEST(MultiArmEkfFusionTest, OnesRowStatesFindEachRowsStates) {
  Eigen::Matrix<double, kM, kN> h = Eigen::Matrix<double, kM, kN>::Zero();
  h(0, 5) = 1.0;
  h(2, 0) = 1.0;
  h(2, 3) = 1.0;
  const OnesRowStates<kM> states = FindOnesRowStates(h);
  EXPECT_EQ(states[0], (std::array<int, 2>{5, -1}));
  EXPECT_EQ(states[1], (std::array<int, 2>{-1, -1}));
  EXPECT_EQ(states[2], (std::array<int, 2>{0, 3}));
}

}  // namespace
}  // namespace birotor
