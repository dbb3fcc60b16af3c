// The setpoint input (setpoint_input.h) and the setpoint <-> reference
// conversion (setpoint.h): followed and extrapolated with its feed-forward,
// held for timeout_s then hover where the vehicle is, and every refusal rule
// counted (defaults of SetpointParams).
#include "controller/setpoint_input.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace birotor {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Setpoint At(int64_t utime, double x_m, double z_m) {
  static int32_t seq = 0;  // one publisher: every setpoint the next seq
  Setpoint s;
  s.seq = seq++;
  s.utime = utime;
  s.x_m = x_m;
  s.z_m = z_m;
  return s;
}

TEST(SetpointTest, ReferenceExtrapolatesWithTheFeedForward) {
  Setpoint s = At(0, 1.0, 2.0);
  s.x_dot_m_s = 0.5;
  s.z_ddot_m_s2 = 2.0;  // x_ddot and z_dot NaN: taken as 0
  const ReferencePoint r = ReferenceFromSetpoint(s, 0.1);
  // p = p0 + v dt + a dt^2 / 2: x = 1 + 0.05, z = 2 + 0.01; v = (0.5, 0.2).
  EXPECT_DOUBLE_EQ(r.position_m.x(), 1.05);
  EXPECT_DOUBLE_EQ(r.position_m.y(), 2.01);
  EXPECT_DOUBLE_EQ(r.velocity_m_s.y(), 0.2);
  EXPECT_DOUBLE_EQ(r.acceleration_m_s2.x(), 0.0);
  const Setpoint back = SetpointFromReference(ReferenceFromSetpoint(s), 7, 3);
  EXPECT_EQ(back.utime, 7);
  EXPECT_EQ(back.seq, 3);
  EXPECT_DOUBLE_EQ(back.x_dot_m_s, 0.5);
  EXPECT_DOUBLE_EQ(back.z_dot_m_s, 0.0);
}

// The rules before shaping: limits so wide that every step here is followed
// exactly (a 0.5 m step in 10 ms is 50 m/s).
SetpointParams Unshaped() {
  SetpointParams params;
  params.max_speed_m_s = 100.0;
  params.max_accel_m_s2 = 100.0;
  return params;
}

TEST(SetpointInputTest, FollowsHoldsThenHoversWhereItIs) {
  const SetpointParams params = Unshaped();
  SetpointInput input(params);
  input.SetStart(Eigen::Vector2d(0.0, 1.0));
  EXPECT_EQ(input.At(0, Eigen::Vector2d::Zero()).position_m.y(), 1.0);
  EXPECT_EQ(input.state(), SetpointState::kHoldStart);
  ASSERT_TRUE(input.Offer(At(10000, 0.2, 1.1), 10000));
  EXPECT_DOUBLE_EQ(input.At(20000, Eigen::Vector2d::Zero()).position_m.x(), 0.2);
  EXPECT_EQ(input.state(), SetpointState::kFollowing);
  // Held until timeout_s (0.5 s) after its stamp, then the vehicle's position.
  EXPECT_DOUBLE_EQ(input.At(510000, Eigen::Vector2d(5.0, 5.0)).position_m.x(), 0.2);
  const ReferencePoint here = input.At(520000, Eigen::Vector2d(0.25, 1.05));
  EXPECT_EQ(input.state(), SetpointState::kHoldHere);
  EXPECT_DOUBLE_EQ(here.position_m.x(), 0.25);
  EXPECT_DOUBLE_EQ(input.At(900000, Eigen::Vector2d(3.0, 3.0)).position_m.y(), 1.05);
  EXPECT_EQ(input.counters().timeouts, 1);
  // A new setpoint near the hover point is followed again.
  EXPECT_TRUE(input.Offer(At(900000, 0.3, 1.0), 900000));
  EXPECT_DOUBLE_EQ(input.At(910000, Eigen::Vector2d::Zero()).position_m.x(), 0.3);
  EXPECT_EQ(input.state(), SetpointState::kFollowing);
}

TEST(SetpointInputTest, HeldSetpointStopsExtrapolatingAfterTheLimit) {
  SetpointInput input{SetpointParams()};
  Setpoint s = At(0, 0.0, 0.0);
  s.x_dot_m_s = 1.0;
  ASSERT_TRUE(input.Offer(s, 0));
  // max_extrapolation_s 0.05: x = 1 m/s x 0.05 s, velocity dropped beyond it.
  const ReferencePoint r = input.At(200000, Eigen::Vector2d::Zero());
  EXPECT_DOUBLE_EQ(r.position_m.x(), 0.05);
  EXPECT_DOUBLE_EQ(r.velocity_m_s.x(), 0.0);
}

TEST(SetpointInputTest, EveryRefusalIsCounted) {
  SetpointInput input{SetpointParams()};
  input.SetStart(Eigen::Vector2d::Zero());
  const int64_t now = 1000000;
  EXPECT_FALSE(input.Offer(At(now, kNaN, 0.0), now));
  EXPECT_FALSE(input.Offer(At(now, 0.0, 101.0), now));  // max_abs_position_m 100
  Setpoint fast = At(now, 0.0, 0.0);
  fast.z_dot_m_s = 5.5;  // max_feed_forward_speed_m_s 5
  EXPECT_FALSE(input.Offer(fast, now));
  EXPECT_EQ(input.counters().rejected_invalid, 3);
  EXPECT_FALSE(input.Offer(At(now + 100001, 0.0, 0.0), now));  // future_window_s 0.1
  EXPECT_FALSE(input.Offer(At(now - 500001, 0.0, 0.0), now));  // older than timeout_s 0.5
  EXPECT_EQ(input.counters().rejected_stamp, 2);
  EXPECT_FALSE(input.Offer(At(now, 0.51, 0.0), now));  // max_jump_m 0.5 from the reference
  EXPECT_EQ(input.counters().rejected_jump, 1);
  EXPECT_TRUE(input.Offer(At(now, 0.1, 0.0), now));
  EXPECT_FALSE(input.Offer(At(now, 0.1, 0.0), now));
  EXPECT_EQ(input.counters().rejected_out_of_order, 1);
  EXPECT_FALSE(input.Offer(At(now + 1999, 0.1, 0.0), now));  // min_interval_s 2 ms
  EXPECT_EQ(input.counters().rejected_rate, 1);
  EXPECT_TRUE(input.Offer(At(now + 2000, 0.1, 0.0), now));
  EXPECT_EQ(input.counters().received, 10);
  EXPECT_EQ(input.counters().accepted, 2);
}

}  // namespace
}  // namespace birotor
