// The one fusion path (estimator/kalman_fusion.h): the Joseph form against
// the textbook product for any gain, the Kalman update's numbers on a case
// worked by hand, the gate (a NaN NIS is never fused, before or after the
// rejection limit, with the Kalman gain or a fixed gain) and the inflation
// policy. The EKF's models give the badly scaled 11-state case; a 3-state
// case shows the path is generic over the state size; the fusion on the
// leading states (LeadingStates, UpdateTrailingStates) equals the one on all.
#include "estimator/kalman_fusion.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <random>

#include "estimator/ekf_model.h"

namespace birotor {
namespace {

using State3 = Eigen::Matrix<double, 3, 1>;
using Matrix3 = Eigen::Matrix<double, 3, 3>;
using Reading1 = Eigen::Matrix<double, 1, 1>;

// z = x0, R = 1, P = diag(3, 2, 1) with P01 = 1, x = 0, z = 2. By hand:
// S = P00 + R = 4, NIS = 2^2 / 4 = 1, K = P H^T / S = (0.75, 0.25, 0),
// x+ = K z = (1.5, 0.5, 0), P+ = P - K S K^T: P00 = 3 - 2.25 = 0.75,
// P01 = 1 - 0.75 = 0.25, P11 = 2 - 0.25 = 1.75, P22 = 1.
struct ScalarCase {
  MeasurementLinearization<1, 3> at;
  Reading1 noise = Reading1::Constant(1.0);
  State3 x = State3::Zero();
  Matrix3 cov;
  ScalarCase() {
    at.jacobian << 1.0, 0.0, 0.0;
    at.predicted(0) = 0.0;
    cov << 3.0, 1.0, 0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 1.0;
  }
};

TEST(FuseMeasurementTest, MatchesTheKalmanUpdateWorkedByHand) {
  ScalarCase c;
  const FusionReport report =
      FuseMeasurement(c.at, c.noise, Reading1(2.0), {FusionSource::kGyro, 123, 25.0}, &c.x, &c.cov);
  EXPECT_EQ(report.outcome, FusionOutcome::kFused);
  EXPECT_EQ(report.source, FusionSource::kGyro);
  EXPECT_EQ(report.utime, 123);
  EXPECT_EQ(report.size, 1);
  EXPECT_DOUBLE_EQ(report.innovation(0), 2.0);
  EXPECT_DOUBLE_EQ(report.innovation_variance(0), 4.0);
  EXPECT_DOUBLE_EQ(report.nis, 1.0);
  EXPECT_EQ(report.gate, 25.0);
  EXPECT_FALSE(report.fused_after_inflation);
  EXPECT_NEAR(c.x(0), 1.5, 1e-15);
  EXPECT_NEAR(c.x(1), 0.5, 1e-15);
  EXPECT_EQ(c.x(2), 0.0);
  EXPECT_NEAR(c.cov(0, 0), 0.75, 1e-15);
  EXPECT_NEAR(c.cov(0, 1), 0.25, 1e-15);
  EXPECT_NEAR(c.cov(1, 1), 1.75, 1e-15);
  EXPECT_NEAR(c.cov(2, 2), 1.0, 1e-15);
}

// A fixed gain (an observer's) is used as given; P by the Joseph form:
// K = (0.5, 0, 0): x+ = (1, 0, 0), P00+ = (1 - 0.5)^2 3 + 0.5^2 1 = 1,
// P01+ = (1 - 0.5) 1 = 0.5, P11 unchanged.
TEST(FuseMeasurementTest, UsesAFixedGainWithTheJosephForm) {
  ScalarCase c;
  const Eigen::Matrix<double, 3, 1> gain(0.5, 0.0, 0.0);
  const FusionReport report =
      FuseMeasurement(c.at, c.noise, Reading1(2.0), {FusionSource::kGyro, 1, 25.0}, &c.x, &c.cov, &gain);
  EXPECT_EQ(report.outcome, FusionOutcome::kFused);
  EXPECT_NEAR(c.x(0), 1.0, 1e-15);
  EXPECT_EQ(c.x(1), 0.0);
  EXPECT_NEAR(c.cov(0, 0), 1.0, 1e-15);
  EXPECT_NEAR(c.cov(0, 1), 0.5, 1e-15);
  EXPECT_NEAR(c.cov(1, 1), 2.0, 1e-15);
}

// NIS 9 / 4 = 2.25 against a gate of 2: rejected, nothing changes; a NaN
// reading is rejected even without a gate.
TEST(FuseMeasurementTest, TheGateRejectsLargeAndNanInnovations) {
  ScalarCase c;
  const Matrix3 before = c.cov;
  FusionReport report = FuseMeasurement(c.at, c.noise, Reading1(3.0), {FusionSource::kStrain, 1, 2.0}, &c.x, &c.cov);
  EXPECT_EQ(report.outcome, FusionOutcome::kRejectedGate);
  EXPECT_DOUBLE_EQ(report.nis, 2.25);
  EXPECT_EQ(c.x, State3::Zero());
  EXPECT_EQ(c.cov, before);
  report = FuseMeasurement(c.at, c.noise, Reading1(std::numeric_limits<double>::quiet_NaN()),
                           {FusionSource::kStrain, 2, std::numeric_limits<double>::infinity()}, &c.x, &c.cov);
  EXPECT_EQ(report.outcome, FusionOutcome::kRejectedGate);
  EXPECT_TRUE(c.x.allFinite());
}

// Limit 3: two rejections, then the third is fused after the inflation; the
// count starts again.
TEST(GateWithInflationTest, FusesAfterTheLimitWithTheInflatedCovariance) {
  ScalarCase c;
  GateWithInflation gate(3);
  int inflations = 0;
  const auto inflate = [&inflations](Matrix3* cov) {
    ++inflations;
    (*cov)(1, 1) += 1.0;
  };
  const FusionRequest request{FusionSource::kStrain, 1, 2.0};
  for (int k = 0; k < 2; ++k) {
    const FusionReport report = gate.Fuse(c.at, c.noise, Reading1(3.0), request, &c.x, &c.cov, inflate);
    EXPECT_EQ(report.outcome, FusionOutcome::kRejectedGate);
    EXPECT_EQ(gate.consecutive_rejected(), k + 1);
  }
  EXPECT_EQ(inflations, 0);
  const FusionReport report = gate.Fuse(c.at, c.noise, Reading1(3.0), request, &c.x, &c.cov, inflate);
  EXPECT_EQ(report.outcome, FusionOutcome::kFused);
  EXPECT_TRUE(report.fused_after_inflation);
  EXPECT_EQ(report.gate, 2.0);  // the gate it failed, not the ungated fusion's
  EXPECT_DOUBLE_EQ(report.nis, 2.25);
  EXPECT_EQ(inflations, 1);
  EXPECT_EQ(gate.consecutive_rejected(), 0);
  // K = (0.75, 0.25, 0) (the inflated P11 is not in P H^T): x0 = 0.75 * 3.
  EXPECT_NEAR(c.x(0), 2.25, 1e-15);
}

// The disagreement of the two former copies: after the rejection limit a NaN
// NIS was rejected by the EKF and fused by the linear methods. One path: it
// is rejected, with the Kalman gain and with a fixed gain, and the state
// stays finite.
TEST(GateWithInflationTest, ANanReadingIsNeverFusedAfterTheLimit) {
  const Eigen::Matrix<double, 3, 1> fixed_gain(0.5, 0.0, 0.0);
  for (const Eigen::Matrix<double, 3, 1>* gain :
       {static_cast<const Eigen::Matrix<double, 3, 1>*>(nullptr), &fixed_gain}) {
    ScalarCase c;
    GateWithInflation gate(2);
    const Reading1 nan(std::numeric_limits<double>::quiet_NaN());
    for (int k = 0; k < 5; ++k) {
      const FusionReport report = gate.Fuse(
          c.at, c.noise, nan, {FusionSource::kStrain, k, 30.0}, &c.x, &c.cov, [](Matrix3* cov) { (*cov)(1, 1) += 1.0; },
          gain);
      EXPECT_EQ(report.outcome, FusionOutcome::kRejectedGate) << k;
      EXPECT_FALSE(report.fused_after_inflation);
    }
    EXPECT_TRUE(c.x.allFinite());
    EXPECT_TRUE(c.cov.allFinite());
  }
}

// A badly scaled but valid covariance, as in the filter (b ~ 1e-5, omega ~ 10).
EkfMatrix RandomCovariance(std::mt19937* rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double kScale[kEkfStateSize] = {1e-5, 1e-5, 0.1, 0.01, 0.01, 10.0, 10.0, 0.1, 0.1, 1e-5, 1e-5, 0.1, 0.1, 0.1};
  EkfMatrix root;
  for (int i = 0; i < kEkfStateSize; ++i) {
    for (int j = 0; j < kEkfStateSize; ++j) root(i, j) = n(*rng) * kScale[i];
  }
  return root * root.transpose();
}

// The textbook Joseph form, dense: (I - K H) P (I - K H)^T + K R K^T.
// P+ against P+ of another form, to round-off relative to the scale of each
// entry's row and column in the prior P.
void ExpectSameCovariance(const EkfMatrix& actual, const EkfMatrix& expected, const EkfMatrix& prior,
                          double relative = 1e-12) {
  for (int i = 0; i < kEkfStateSize; ++i) {
    for (int j = 0; j < kEkfStateSize; ++j) {
      EXPECT_NEAR(actual(i, j), expected(i, j), relative * std::sqrt(prior(i, i) * prior(j, j))) << i << ", " << j;
    }
  }
}

template <int M>
EkfMatrix TextbookJoseph(const EkfMatrix& p, const Eigen::Matrix<double, kEkfStateSize, M>& k,
                         const Eigen::Matrix<double, M, kEkfStateSize>& h, const Eigen::Matrix<double, M, M>& r) {
  const EkfMatrix i_kh = EkfMatrix::Identity() - k * h;
  return i_kh * p * i_kh.transpose() + k * r * k.transpose();
}

// With a gain that is NOT the Kalman gain the expanded form P - K S K^T is
// wrong; the Joseph form holds for any gain, so this is what tells them apart.
TEST(JosephCovarianceTest, MatchesTheTextbookFormForANonOptimalGain) {
  std::mt19937 rng(13);
  std::normal_distribution<double> n(0.0, 1.0);
  const StrainMeasurementModel strain(2e-5);
  const MotorSpeedMeasurementModel motor(5.0);
  // H of z_i = g_i b_i + e_i at g = 1.1, b = -/+ 2e-3 rad (the scale's column is not zero).
  EkfState x0 = EkfState::Zero();
  x0(kStrainScale1) = x0(kStrainScale2) = 1.1;
  x0(kDeflection1) = -2e-3;
  x0(kDeflection2) = 2e-3;
  const StrainMeasurementModel::Jacobian strain_h = strain.Linearize(x0).jacobian;
  for (int trial = 0; trial < 20; ++trial) {
    const EkfMatrix p = RandomCovariance(&rng);
    const Eigen::Matrix2d s = strain_h * p * strain_h.transpose() + strain.noise;
    Eigen::Matrix<double, kEkfStateSize, 2> k = p * strain_h.transpose() * s.inverse();
    for (int i = 0; i < kEkfStateSize; ++i) {
      for (int j = 0; j < 2; ++j) k(i, j) *= 1.0 + 0.3 * n(rng);  // 30 % off the optimum
    }
    const EkfMatrix joseph = JosephCovariance<kEkfStateSize, 2>(p, k, strain_h, strain.noise);
    const EkfMatrix textbook = TextbookJoseph<2>(p, k, strain_h, strain.noise);
    const EkfMatrix expanded = p - k * s * k.transpose();  // only right at the optimal gain
    ExpectSameCovariance(joseph, textbook, p);
    EXPECT_GT((expanded - textbook).cwiseAbs().maxCoeff(), 1e-3 * textbook.cwiseAbs().maxCoeff());

    const Eigen::Matrix<double, kEkfStateSize, 2> k2 = Eigen::Matrix<double, kEkfStateSize, 2>::Random() * 0.01;
    const EkfMatrix joseph2 = JosephCovariance<kEkfStateSize, 2>(p, k2, motor.h_jacobian, motor.noise);
    const EkfMatrix textbook2 = TextbookJoseph<2>(p, k2, motor.h_jacobian, motor.noise);
    EXPECT_LE((joseph2 - textbook2).cwiseAbs().maxCoeff(), 1e-12 * textbook2.cwiseAbs().maxCoeff());
  }
}

// At the optimal gain all forms agree: P+ = P - K S K^T.
TEST(JosephCovarianceTest, EqualsTheStandardUpdateAtTheKalmanGain) {
  std::mt19937 rng(17);
  const GyroMeasurementModel gyro(0.005);
  const EkfMatrix p = RandomCovariance(&rng);
  const Eigen::Matrix<double, 1, 1> s = gyro.h_jacobian * p * gyro.h_jacobian.transpose() + gyro.noise;
  const Eigen::Matrix<double, kEkfStateSize, 1> k = p * gyro.h_jacobian.transpose() * s.inverse();
  const EkfMatrix joseph = JosephCovariance<kEkfStateSize, 1>(p, k, gyro.h_jacobian, gyro.noise);
  const EkfMatrix standard = p - k * s * k.transpose();
  ExpectSameCovariance(joseph, standard, p, 1e-10);
}

// 1500 updates of a badly scaled covariance: symmetric to round-off (the
// factored product is not symmetric by construction) and positive definite.
TEST(JosephCovarianceTest, KeepsCovarianceSymmetricPositiveDefinite) {
  std::mt19937 rng(13);
  std::normal_distribution<double> n(0.0, 1.0);
  EkfMatrix cov = RandomCovariance(&rng);
  EkfState x = EkfState::Zero();
  x(kStrainScale1) = x(kStrainScale2) = x(kBodyMassScale) = 1.0;
  const StrainMeasurementModel strain(2e-5);
  const MotorSpeedMeasurementModel motor(5.0);
  for (int k = 0; k < 1000; ++k) {
    const StrainMeasurementModel::Vector z(1e-5 * n(rng), 1e-5 * n(rng));
    const StrainMeasurementModel::Linearization s = strain.Linearize(x);
    KalmanUpdate(s, strain.noise, ComputeInnovation(s, strain.noise, cov, z), &x, &cov);
    if (k % 2 == 0) {
      const MotorSpeedMeasurementModel::Vector w(5.0 * n(rng), 5.0 * n(rng));
      const MotorSpeedMeasurementModel::Linearization m = motor.Linearize(x);
      KalmanUpdate(m, motor.noise, ComputeInnovation(m, motor.noise, cov, w), &x, &cov);
    }
  }
  const EkfState d = cov.diagonal().cwiseSqrt().cwiseInverse();
  const EkfMatrix scaled = d.asDiagonal() * cov * d.asDiagonal();  // correlations
  EXPECT_LE((scaled - scaled.transpose()).cwiseAbs().maxCoeff(), 1e-9);
  Eigen::LLT<EkfMatrix> llt(0.5 * (scaled + scaled.transpose()));
  EXPECT_EQ(llt.info(), Eigen::Success);
  // The gauge reading g1 b1 + e1 cannot be less certain than R = (2e-5)^2 after an update.
  const StrainMeasurementModel::Jacobian strain_h = strain.Linearize(x).jacobian;
  const Eigen::Matrix2d reading_cov = strain_h * cov * strain_h.transpose();
  EXPECT_LE(reading_cov(0, 0), 4e-10);
}

// The EKF with no slow parameter learned (or frozen) fuses on its leading 11
// states (LeadingStates): with the trailing rows and columns of P zero, x and
// P come out as the fusion on all 14 gives them (the skipped terms are exact
// zeros; only the order of the sums may differ: 1e-13 of the entry's scale),
// and the trailing states are left alone.
TEST(LeadingStatesTest, FusesAsAllStatesWhenTheTrailingOnesHaveZeroCovariance) {
  constexpr int n = kStrainScale1;
  std::mt19937 rng(29);
  std::normal_distribution<double> normal(0.0, 1.0);
  const StrainMeasurementModel strain(2e-5);
  EkfState x = EkfState::Zero();
  x(kDeflection1) = -2e-3;
  x(kDeflection2) = 2e-3;
  x(kStrainScale1) = 1.1;  // a frozen learned value: H has a non-zero column there
  x(kStrainScale2) = 0.9;
  x(kBodyMassScale) = 1.0;
  for (int trial = 0; trial < 20; ++trial) {
    EkfMatrix p = RandomCovariance(&rng);
    p.rightCols<kEkfStateSize - n>().setZero();
    p.bottomRows<kEkfStateSize - n>().setZero();
    const StrainMeasurementModel::Vector z(x(kDeflection1) + 3e-5 * normal(rng), x(kDeflection2) + 3e-5 * normal(rng));
    const StrainMeasurementModel::Linearization at = strain.Linearize(x);
    EkfState x_all = x;
    EkfMatrix p_all = p;
    const FusionReport all = FuseMeasurement(at, strain.noise, z, {}, &x_all, &p_all);
    Eigen::Matrix<double, n, 1> x_lead = x.head<n>();
    Eigen::Matrix<double, n, n> p_lead = p.topLeftCorner<n, n>();
    const FusionReport lead = FuseMeasurement(LeadingStates<n>(at), strain.noise, z, {}, &x_lead, &p_lead);
    ASSERT_EQ(all.outcome, FusionOutcome::kFused);
    ASSERT_EQ(lead.outcome, FusionOutcome::kFused);
    EXPECT_NEAR(lead.nis, all.nis, 1e-12 * all.nis);
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(x_lead(i), x_all(i), 1e-13 * std::sqrt(p(i, i))) << i;
      for (int j = 0; j < n; ++j) {
        EXPECT_NEAR(p_lead(i, j), p_all(i, j), 1e-13 * std::sqrt(p(i, i) * p(j, j))) << i << ", " << j;
      }
    }
    // The fusion on all states leaves the trailing ones exactly as they were.
    EXPECT_EQ(x_all.tail<kEkfStateSize - n>(), x.tail<kEkfStateSize - n>());
    EXPECT_EQ(p_all.rightCols<kEkfStateSize - n>().cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(p_all.bottomRows<kEkfStateSize - n>().cwiseAbs().maxCoeff(), 0.0);
  }
}

// JosephForm::kCombined, -(A H^T - K R) K^T in one product, is the Joseph
// product of kSeparate to round-off: for a gain 30 % off the optimum (the
// whole update), and in FuseMeasurement at the optimal gain on the leading
// states with the rest trailing (the EKF with slow parameters live: the
// strain on 13 states, the gyro on the 9 dynamic ones). The state update
// does not depend on the form.
TEST(JosephCovarianceTest, CombinedFormIsTheSeparateProduct) {
  std::mt19937 rng(37);
  std::normal_distribution<double> n(0.0, 1.0);
  const StrainMeasurementModel strain(2e-5);
  const GyroMeasurementModel gyro(0.005);
  EkfState x0 = EkfState::Zero();
  x0(kStrainScale1) = 1.1;
  x0(kStrainScale2) = 0.9;
  x0(kDeflection1) = -2e-3;
  x0(kDeflection2) = 2e-3;
  const StrainMeasurementModel::Linearization at = strain.Linearize(x0);
  FusionRequest combined;
  combined.joseph = JosephForm::kCombined;
  for (int trial = 0; trial < 20; ++trial) {
    const EkfMatrix p = RandomCovariance(&rng);
    const Eigen::Matrix<double, 2, kEkfStateSize> h_p = at.jacobian * p;
    const Eigen::Matrix2d s = h_p * at.jacobian.transpose() + strain.noise;
    Eigen::Matrix<double, kEkfStateSize, 2> k = h_p.transpose() * s.inverse();
    for (int i = 0; i < kEkfStateSize; ++i) {
      for (int j = 0; j < 2; ++j) k(i, j) *= 1.0 + 0.3 * n(rng);
    }
    ExpectSameCovariance(
        JosephCovariance<kEkfStateSize, 2>(p, k, h_p, at.jacobian, strain.noise, JosephForm::kCombined),
        JosephCovariance<kEkfStateSize, 2>(p, k, h_p, at.jacobian, strain.noise, JosephForm::kSeparate), p);

    EkfState x = x0;
    for (int i = 0; i < kEkfStateSize; ++i) x(i) += 1e-3 * n(rng) * std::sqrt(p(i, i));
    const Eigen::Vector2d z = at.predicted + Eigen::Vector2d(2e-5 * n(rng), 2e-5 * n(rng));
    EkfState x_separate = x, x_combined = x;
    EkfMatrix p_separate = p, p_combined = p;
    ASSERT_EQ(FuseMeasurement(LeadingStates<kBodyMassScale>(at), strain.noise, z, {}, &x_separate, &p_separate).outcome,
              FusionOutcome::kFused);
    ASSERT_EQ(
        FuseMeasurement(LeadingStates<kBodyMassScale>(at), strain.noise, z, combined, &x_combined, &p_combined).outcome,
        FusionOutcome::kFused);
    EXPECT_EQ(x_combined, x_separate);
    ExpectSameCovariance(p_combined, p_separate, p);

    const GyroMeasurementModel::Vector rate(x(kPitchRate) + 0.005 * n(rng));
    const auto gyro_at = LeadingStates<kDynamicStateSize>(gyro.Linearize(x));
    x_separate = x_combined = x;
    p_separate = p_combined = p;
    FuseMeasurement(gyro_at, gyro.noise, rate, {}, &x_separate, &p_separate);
    FuseMeasurement(gyro_at, gyro.noise, rate, combined, &x_combined, &p_combined);
    EXPECT_EQ(x_combined, x_separate);
    ExpectSameCovariance(p_combined, p_separate, p);
  }
}

// A measurement that reads only the leading K states, the trailing ones live
// (learned, correlated): FuseMeasurement on the leading K with the trailing
// states updated through their cross covariance (UpdateTrailingStates) gives
// the x and P of the fusion on all 14 (the skipped terms are products with
// H's exact zeros: 1e-13 of the entry's scale, as for LeadingStates). The
// EKF's cases: gyro, telemetry and accelerometer on the 9 dynamic states with
// the offsets and slow states trailing, the strain on 13 with the mass.
template <int K, int M>
void ExpectTrailingUpdateAsAllStates(const MeasurementLinearization<M, kEkfStateSize>& at,
                                     const Eigen::Matrix<double, M, M>& noise, std::mt19937* rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  ASSERT_TRUE(at.jacobian.template rightCols<kEkfStateSize - K>().isZero(0.0));
  for (int trial = 0; trial < 10; ++trial) {
    const EkfMatrix p = RandomCovariance(rng);
    EkfState x = EkfState::Zero();
    for (int i = 0; i < kEkfStateSize; ++i) x(i) = 1e-3 * normal(*rng);
    Eigen::Matrix<double, M, 1> z = at.predicted;
    for (int i = 0; i < M; ++i) z(i) += std::sqrt(noise(i, i)) * normal(*rng);
    EkfState x_all = x, x_split = x;
    EkfMatrix p_all = p, p_split = p;
    const FusionReport all = FuseMeasurement(at, noise, z, {}, &x_all, &p_all);
    const FusionReport split = FuseMeasurement(LeadingStates<K>(at), noise, z, {}, &x_split, &p_split);
    ASSERT_EQ(all.outcome, FusionOutcome::kFused);
    ASSERT_EQ(split.outcome, FusionOutcome::kFused);
    EXPECT_NEAR(split.nis, all.nis, 1e-12 * all.nis);
    for (int i = 0; i < kEkfStateSize; ++i) {
      EXPECT_NEAR(x_split(i), x_all(i), 1e-13 * std::sqrt(p(i, i))) << i;
      for (int j = 0; j < kEkfStateSize; ++j) {
        // The fusion on all states is not symmetric to round-off: its mean.
        const double expected = 0.5 * (p_all(i, j) + p_all(j, i));
        EXPECT_NEAR(p_split(i, j), expected, 1e-13 * std::sqrt(p(i, i) * p(j, j))) << i << ", " << j;
      }
    }
    // The trailing block is changed (the test would pass trivially otherwise).
    EXPECT_GT((p_split.bottomRightCorner<kEkfStateSize - K, kEkfStateSize - K>() -
               p.bottomRightCorner<kEkfStateSize - K, kEkfStateSize - K>())
                  .cwiseAbs()
                  .maxCoeff(),
              0.0);
  }
}

TEST(UpdateTrailingStatesTest, FusesAsAllStatesWhenHReadsOnlyTheLeadingOnes) {
  std::mt19937 rng(31);
  const GyroMeasurementModel gyro(0.005);
  const MotorSpeedMeasurementModel motor(5.0);
  const StrainMeasurementModel strain(2e-5);
  EkfState x = EkfState::Zero();
  x(kDeflection1) = -2e-3;
  x(kDeflection2) = 2e-3;
  x(kOmega1) = x(kOmega2) = 460.0;
  x(kThrustScale1) = x(kThrustScale2) = 1.0;
  x(kStrainScale1) = 1.1;
  x(kStrainScale2) = 0.9;
  x(kBodyMassScale) = 1.0;
  const EkfProcessModel process((BirotorParams()));  // the reference vehicle; the mass not a state: no mass column
  ExpectTrailingUpdateAsAllStates<kDynamicStateSize>(gyro.Linearize(x), gyro.noise, &rng);
  ExpectTrailingUpdateAsAllStates<kDynamicStateSize>(motor.Linearize(x), motor.noise, &rng);
  ExpectTrailingUpdateAsAllStates<kDynamicStateSize>(AccelerometerMeasurementModel::Linearize(process, x),
                                                     AccelerometerMeasurementModel(0.05).noise, &rng);
  ExpectTrailingUpdateAsAllStates<kBodyMassScale>(strain.Linearize(x), strain.noise, &rng);
}

// A consider state (KalmanUpdate's consider_states, the EKF's hold through a
// thrust step): its gain row is zero, so it keeps its value and variance, and
// P is the Joseph form of that gain, whether the measurement reads the state
// (state 1, among the leading three) or only correlates with it (state 3,
// trailing: UpdateTrailingStates).
TEST(KalmanUpdateTest, AConsiderStateIsNotMovedAndPIsTheJosephFormOfItsGain) {
  using State4 = Eigen::Matrix<double, 4, 1>;
  using Matrix4 = Eigen::Matrix<double, 4, 4>;
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  Matrix4 root;
  for (int i = 0; i < 16; ++i) root(i / 4, i % 4) = normal(rng);
  const Matrix4 prior = root * root.transpose() + 0.5 * Matrix4::Identity();
  MeasurementLinearization<2, 3> at;  // reads the leading three states
  at.jacobian << 1.0, 0.5, 0.0, 0.0, -0.3, 2.0;
  at.predicted << 0.1, -0.2;
  const Eigen::Matrix2d noise = Eigen::Vector2d(0.4, 0.9).asDiagonal();
  const Eigen::Vector2d z(0.7, 0.3);
  Eigen::Matrix<double, 2, 4> h = Eigen::Matrix<double, 2, 4>::Zero();
  h.leftCols<3>() = at.jacobian;
  for (const int held : {1, 3}) {
    State4 x = State4::Constant(0.25);
    Matrix4 cov = prior;
    const Innovation<2, 3> innovation = ComputeInnovation(at, noise, cov.topLeftCorner<3, 3>(), z);
    const Eigen::Matrix<double, 3, 2>* no_fixed_gain = nullptr;
    KalmanUpdate(at, noise, innovation, &x, &cov, no_fixed_gain, JosephForm::kCombined, 1u << held);
    // Dense: K = P H^T S^-1 with row `held` zero, P+ = (I - K H) P (I - K H)^T + K R K^T.
    const Eigen::Matrix2d s = h * prior * h.transpose() + noise;
    Eigen::Matrix<double, 4, 2> gain = prior * h.transpose() * s.inverse();
    gain.row(held).setZero();
    const Matrix4 factor = Matrix4::Identity() - gain * h;
    const Matrix4 expected = factor * prior * factor.transpose() + gain * noise * gain.transpose();
    const State4 expected_x = State4::Constant(0.25) + gain * (z - at.predicted);
    EXPECT_EQ(x(held), 0.25) << "held " << held;
    EXPECT_EQ(cov(held, held), prior(held, held)) << "held " << held;
    for (int r = 0; r < 4; ++r) {
      EXPECT_NEAR(x(r), expected_x(r), 1e-12) << "held " << held << ", state " << r;
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(cov(r, c), expected(r, c), 1e-12) << held << ": " << r << ", " << c;
    }
  }
}

}  // namespace
}  // namespace birotor
