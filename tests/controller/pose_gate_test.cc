// PoseGate (controller/pose_gate.h): POSE outside the gate is refused; a
// run of pose_reacquire_count (5) mutually consistent refused POSEs is
// re-acquired, an outlier breaks the run; every POSE refused for
// pose_gate_reset_s (0.2 s) resets.
#include "controller/pose_gate.h"

#include <gtest/gtest.h>

namespace birotor {
namespace {

constexpr int64_t kPoseIntervalUs = 10000;  // 100 Hz POSE

PoseSample PoseAt(int64_t utime, double x_m, double z_m) { return PoseSample{utime, 0, x_m, z_m, 0.0}; }

TEST(PoseGateTest, InsideIsFusedFarIsRefused) {
  PoseGate gate{SupervisionParams()};
  const BodyState observer;
  EXPECT_EQ(gate.Check(PoseAt(0, 0.1, 0.2), observer, 0), PoseGate::Verdict::kInside);
  EXPECT_EQ(gate.Check(PoseAt(kPoseIntervalUs, 0.0, 0.31), observer, kPoseIntervalUs), PoseGate::Verdict::kRefused);
}

TEST(PoseGateTest, FiveConsistentPosesAreReacquiredMovingWithTheObserversVelocity) {
  const SupervisionParams params;
  PoseGate gate(params);
  BodyState observer;  // drifted: the vehicle is 1 m higher, climbing at 0.5 m/s as the IMU says
  observer.velocity_m_s = Eigen::Vector2d(0.0, 0.5);
  for (int k = 0; k < params.pose_reacquire_count; ++k) {
    const int64_t t = k * kPoseIntervalUs;
    // 0.5 m/s x 10 ms = 5 mm per POSE, plus 1 mm of noise each way.
    const PoseSample pose = PoseAt(t, 0.0, 1.0 + 0.005 * k + (k % 2 == 0 ? 1e-3 : -1e-3));
    const PoseGate::Verdict expected =
        k + 1 < params.pose_reacquire_count ? PoseGate::Verdict::kRefused : PoseGate::Verdict::kReacquired;
    EXPECT_EQ(gate.Check(pose, observer, t), expected) << k;
  }
}

TEST(PoseGateTest, AnOutlierBreaksTheRun) {
  const SupervisionParams params;
  PoseGate gate(params);
  const BodyState observer;
  int64_t t = 0;
  for (int k = 0; k < 3; ++k, t += kPoseIntervalUs) {
    EXPECT_EQ(gate.Check(PoseAt(t, 0.0, 1.0), observer, t), PoseGate::Verdict::kRefused);
  }
  // 5 cm off the run (pose_reacquire_position_m 2 cm): a new run of one.
  EXPECT_EQ(gate.Check(PoseAt(t, 0.05, 1.0), observer, t), PoseGate::Verdict::kRefused);
  t += kPoseIntervalUs;
  for (int k = 0; k < params.pose_reacquire_count - 2; ++k, t += kPoseIntervalUs) {
    EXPECT_EQ(gate.Check(PoseAt(t, 0.05, 1.0), observer, t), PoseGate::Verdict::kRefused) << k;
  }
  EXPECT_EQ(gate.Check(PoseAt(t, 0.05, 1.0), observer, t), PoseGate::Verdict::kReacquired);
}

TEST(PoseGateTest, InconsistentPosesStillResetAfterTheResetTime) {
  const SupervisionParams params;
  PoseGate gate(params);
  const BodyState observer;
  // Alternating 10 cm apart: never a run of two, all refused for 0.2 s.
  int64_t t = 0;
  for (; t < static_cast<int64_t>(params.pose_gate_reset_s * 1e6); t += kPoseIntervalUs) {
    const double x_m = (t / kPoseIntervalUs) % 2 == 0 ? 0.0 : 0.1;
    EXPECT_EQ(gate.Check(PoseAt(t, x_m, 1.0), observer, t), PoseGate::Verdict::kRefused) << t;
  }
  EXPECT_EQ(gate.Check(PoseAt(t, 0.0, 1.0), observer, t), PoseGate::Verdict::kReset);
}

}  // namespace
}  // namespace birotor
