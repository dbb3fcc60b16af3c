// The N-arm EKF on a redundant vehicle (config/vehicles/quadrotor.yaml: four
// rotors for the three wrench rows): the offset combination the rigid body
// cannot see (estimator/multi_arm_offset_hold.h) and short runs of the
// simulator (evaluation/multi_arm_accuracy.h). docs/estimator.md, "A vehicle
// with more rotors than the body pins". Figures measured on this commit.
#include <gtest/gtest.h>

#include <cmath>

#include "estimator/multi_arm_offset_hold.h"
#include "evaluation/eval_runner.h"
#include "evaluation/multi_arm_accuracy.h"
#include "multi_arm_source_files.h"

namespace birotor {
namespace {

// The birotor (N = 2) and the trirotor (N = 3) have no wrench null space:
// no hold, so their filters are the ones before it.
TEST(UnseenOffsetHoldTest, NoneWithoutARedundantRotor) {
  EXPECT_FALSE(UnseenOffsetHold<2>(Vehicle("birotor")).active);
  EXPECT_FALSE(UnseenOffsetHold<3>(Vehicle("trirotor")).active);
}

// The quadrotor's one pattern: offsets de_i = -l_i df_i / k_eff,i for the
// null force df ~ [-0.41, -0.41, 0.58, 0.58] (levers -L, +L, +L, -L), so
// keep = I - u u^T with u ~ [0.41, -0.41, 0.58, -0.58] up to the sign: rank 3,
// and it leaves the patterns the body does see (e.g. all offsets equal) whole
// but for their share along u.
TEST(UnseenOffsetHoldTest, QuadrotorHoldsTheNullForcePattern) {
  const LeadingGainHold<4> hold = UnseenOffsetHold<4>(Vehicle("quadrotor"));
  ASSERT_TRUE(hold.active);
  Eigen::Vector4d u(0.408248, -0.408248, 0.577350, -0.577350);
  EXPECT_LT((hold.keep * u).norm(), 1e-3);  // removed (k_eff differs per arm in the fourth digit)
  EXPECT_NEAR(hold.keep.trace(), 3.0, 1e-12);
  EXPECT_LT((hold.keep - hold.keep.transpose()).norm(), 1e-15);
  EXPECT_LT((hold.keep * hold.keep - hold.keep).norm(), 1e-12);  // a projection
}

// The held update on a small random problem (3 states, the first 2 held
// along u, 2 measurements): u^T x's leading part does not move, and P+ is
// the Joseph form (I - K H) P (I - K H)^T + K R K^T of the held gain K
// exactly (to rounding): the covariance of the estimate the hold makes.
TEST(UnseenOffsetHoldTest, HeldUpdateIsTheJosephFormOfItsGain) {
  Eigen::Matrix3d root;
  root << 1.0, 0.2, -0.3, 0.4, 0.9, 0.1, -0.2, 0.3, 1.1;
  Eigen::Matrix3d p = root * root.transpose();
  Eigen::Matrix<double, 2, 3> h;
  h << 1.0, 1.0, 0.0, 0.0, 1.0, 1.0;
  const Eigen::Matrix2d r = Eigen::Vector2d(0.1, 0.2).asDiagonal();
  const Eigen::Vector2d residual(0.3, -0.5);
  const Eigen::Vector2d u = Eigen::Vector2d(1.0, -2.0).normalized();
  LeadingGainHold<2> hold;
  hold.active = true;
  hold.keep -= u * u.transpose();
  const Eigen::Matrix<double, 2, 3> h_p = h * p;
  const Eigen::Matrix2d s = h_p * h.transpose() + r;
  Eigen::Vector3d x(0.1, 0.2, 0.3);
  Eigen::Matrix3d updated = p;
  SymmetricJosephUpdate(h_p, s, Eigen::Matrix2d(s.inverse()), residual, &x, &updated, &hold);
  EXPECT_NEAR(u.dot(x.head<2>()), u.dot(Eigen::Vector2d(0.1, 0.2)), 1e-15);
  Eigen::Matrix<double, 3, 2> gain = p * h.transpose() * s.inverse();
  gain.topRows<2>() = hold.keep * gain.topRows<2>();
  const Eigen::Matrix3d i_kh = Eigen::Matrix3d::Identity() - gain * h;
  const Eigen::Matrix3d joseph = i_kh * p * i_kh.transpose() + gain * r * gain.transpose();
  EXPECT_LT((updated - joseph).norm(), 1e-13);
}

// 4 s of each flight on the quadrotor. Measured (hold on): MAE hover 0.0569 /
// 0.0532 / 0.0471 / 0.0432 N, gentle 0.0560 / 0.0569 / 0.0460 / 0.0476 N
// (without the hold 2-4x these on 20 s of hover); the 2-sigma share 1.000:
// the sigma carries the gauge offsets' prior along the pattern, which the
// simulator's ideal gauges do not realise. Asserted: MAE below 1.3x, share
// at least 0.93, VALID, no false alarm.
TEST(MultiArmRedundantTest, QuadrotorHoverAndGentleAtTheGaugeFloor) {
  const double measured_mae_n[2][4] = {{0.0569, 0.0532, 0.0471, 0.0432}, {0.0560, 0.0569, 0.0460, 0.0476}};
  const char* scenarios[2] = {"hover", "gentle"};
  for (int s = 0; s < 2; ++s) {
    const MultiArmAccuracy r = RunMultiArmAccuracy(
        Vehicle("quadrotor"), ScenarioFor(scenarios[s], {"scenario.duration_s=4"}, 4), Config(), EvalOptions());
    ASSERT_EQ(r.n_rotors, 4);
    EXPECT_EQ(r.nonfinite, 0);
    for (size_t i = 0; i < 4; ++i) {
      EXPECT_LT(r.rotor[i].mae_n, 1.3 * measured_mae_n[s][i]) << scenarios[s] << " rotor " << i + 1;
      EXPECT_GE(r.rotor[i].share_within_2sigma, 0.93) << scenarios[s] << " rotor " << i + 1;
    }
    EXPECT_GT(r.valid_share, 0.99) << scenarios[s];
    EXPECT_EQ(r.false_alarms, 0) << scenarios[s];
  }
}

// A 25 % loss on rotor 2 at 2 s of a 4 s hover. Measured: flagged 9 ms after
// the step, no false alarm; asserted within 15 ms and not before the 2 ms
// persistence (fault_persistence_s).
TEST(MultiArmRedundantTest, QuadrotorLossOnRotor2IsFlagged) {
  const MultiArmAccuracy r = RunMultiArmAccuracy(
      Vehicle("quadrotor"),
      ScenarioFor("thrust_loss",
                  {"scenario.duration_s=4", "faults.thrust_steps=[{time_s: 2.0, rotor: 2, scale: 0.75}]"}, 4),
      Config(), EvalOptions());
  EXPECT_EQ(r.step_rotor, 2);
  EXPECT_LE(r.detection_delay_s, 0.015);
  EXPECT_GE(r.detection_delay_s, 0.002);
  EXPECT_EQ(r.false_alarms, 0);
}

}  // namespace
}  // namespace birotor
