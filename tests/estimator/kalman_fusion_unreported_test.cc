// FuseMeasurementUnreported and GateWithInflation::FuseUnreported
// (estimator/kalman_fusion.h), the N-arm EKF's fusion for measurements larger
// than a FusionReport: the same x, P, outcome and NIS as FuseMeasurement and
// GateWithInflation::Fuse, bit for bit, on random problems of the size that
// both accept (M = 2).
#include <gtest/gtest.h>

#include <random>

#include "estimator/kalman_fusion.h"

namespace birotor {
namespace {

constexpr int kN = 6, kM = 2;
using State = Eigen::Matrix<double, kN, 1>;
using Cov = Eigen::Matrix<double, kN, kN>;

struct Problem {
  MeasurementLinearization<kM, kN> at;
  Eigen::Matrix<double, kM, kM> noise;
  Eigen::Matrix<double, kM, 1> z;
  State x;
  Cov p;
};

Problem RandomProblem(std::mt19937* rng, double innovation_scale) {
  std::normal_distribution<double> g(0.0, 1.0);
  Problem out;
  for (int r = 0; r < kM; ++r) {
    out.at.predicted(r) = g(*rng);
    out.z(r) = out.at.predicted(r) + innovation_scale * g(*rng);
    for (int c = 0; c < kN; ++c) out.at.jacobian(r, c) = g(*rng);
  }
  out.noise = Eigen::Matrix<double, kM, kM>::Identity() * 0.1;
  Cov a;
  for (int r = 0; r < kN; ++r) {
    out.x(r) = g(*rng);
    for (int c = 0; c < kN; ++c) a(r, c) = g(*rng);
  }
  out.p = a * a.transpose() + Cov::Identity();
  return out;
}

TEST(FuseMeasurementUnreportedTest, SameAsFuseMeasurement) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const Problem problem = RandomProblem(&rng, trial % 2 == 0 ? 0.1 : 10.0);
    State x1 = problem.x, x2 = problem.x;
    Cov p1 = problem.p, p2 = problem.p;
    const FusionReport report =
        FuseMeasurement(problem.at, problem.noise, problem.z, {FusionSource::kStrain, 0, 9.0}, &x1, &p1);
    double nis = 0;
    const FusionOutcome outcome = FuseMeasurementUnreported(problem.at, problem.noise, problem.z, 9.0, &x2, &p2, &nis);
    EXPECT_EQ(outcome, report.outcome);
    EXPECT_EQ(nis, report.nis);
    EXPECT_EQ(x1, x2);
    EXPECT_EQ(p1, p2);
  }
}

TEST(FuseMeasurementUnreportedTest, GateWithInflationSameAsFuse) {
  std::mt19937 rng(9);
  GateWithInflation reported(3), unreported(3);
  const auto inflate = [](Cov* p) { (*p)(0, 0) += 0.5; };
  for (int trial = 0; trial < 200; ++trial) {
    const Problem problem = RandomProblem(&rng, trial % 10 < 6 ? 10.0 : 0.1);
    State x1 = problem.x, x2 = problem.x;
    Cov p1 = problem.p, p2 = problem.p;
    const FusionReport report =
        reported.Fuse(problem.at, problem.noise, problem.z, {FusionSource::kStrain, 0, 9.0}, &x1, &p1, inflate);
    bool after_inflation = false;
    const FusionOutcome outcome =
        unreported.FuseUnreported(problem.at, problem.noise, problem.z, 9.0, &x2, &p2, inflate, &after_inflation);
    EXPECT_EQ(outcome, report.outcome) << trial;
    EXPECT_EQ(after_inflation, report.fused_after_inflation) << trial;
    EXPECT_EQ(unreported.consecutive_rejected(), reported.consecutive_rejected()) << trial;
    EXPECT_EQ(x1, x2) << trial;
    EXPECT_EQ(p1, p2) << trial;
  }
}

}  // namespace
}  // namespace birotor
