// The condensed QP: the answer at hover, the bounds and rate limits held when
// the reference asks for more, the soft tilt limit, and the three alglib
// algorithms agreeing on random problems.
#include "controller/mpc_qp.h"

#include <gtest/gtest.h>

#include <random>

#include "controller/mpc_controller.h"
#include "controller/position_attitude_law.h"

namespace birotor {
namespace {

struct Problem {
  MpcPredictionModel model{BirotorParams()};
  MpcParams params;
  double hover_rad_s = RotorSpeedForThrust(BirotorParams(), model.hover_force_n(), 1.0);

  MpcQpData Data(const MpcState& s0, const Eigen::Vector2d& target_m, const Eigen::Vector2d& last) const {
    MpcQpData data;
    data.initial = s0;
    data.step = Generalized(model.Linearize(s0, last, MpcModelContext(), params.step_s));
    data.reference = Eigen::MatrixXd::Zero(kMpcStateSize, params.horizon_steps);
    for (int k = 0; k < params.horizon_steps; ++k) {
      data.reference(kMpcX, k) = target_m.x();
      data.reference(kMpcZ, k) = target_m.y();
      data.reference(kMpcOmega1, k) = data.reference(kMpcOmega2, k) = hover_rad_s;
    }
    data.feed_forward_rad_s = Eigen::MatrixXd::Constant(kMpcInputSize, params.horizon_steps, hover_rad_s);
    data.last_command_rad_s = last;
    data.command_period_s = 1.0 / params.rate_hz;
    return data;
  }
  MpcState HoverState() const {
    MpcState s = MpcState::Zero();
    s(kMpcOmega1) = s(kMpcOmega2) = hover_rad_s;
    return s;
  }
};

TEST(MpcQpTest, HoverAtTheReferenceKeepsHoverSpeeds) {
  Problem p;
  MpcQp qp(p.params, kMpcInputSize, 1200.0, MpcController::TerminalWeight(p.model, p.params));
  const MpcQpSolution sol =
      qp.Solve(p.Data(p.HoverState(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Constant(p.hover_rad_s)));
  ASSERT_EQ(sol.status, MpcSolveStatus::kSolved);
  // Hover speed 698.55 rad/s (reference-vehicle.md); the interior point stops within ~0.01 rad/s.
  EXPECT_NEAR(sol.first_command_rad_s(0), p.hover_rad_s, 0.05);
  EXPECT_NEAR(sol.first_command_rad_s(1), p.hover_rad_s, 0.05);
  EXPECT_NEAR(sol.tilt_slack_rad, 0.0, 1e-3);  // the interior point keeps eps off its bound
}

TEST(MpcQpTest, BoundsAndRateLimitsHoldForAFarReference) {
  Problem p;
  MpcQp qp(p.params, kMpcInputSize, 1200.0, MpcController::TerminalWeight(p.model, p.params));
  const Eigen::Vector2d last = Eigen::Vector2d::Constant(p.hover_rad_s);
  const MpcQpSolution up = qp.Solve(p.Data(p.HoverState(), Eigen::Vector2d(0.0, 5.0), last));
  ASSERT_EQ(up.status, MpcSolveStatus::kSolved);
  // 5 m up: both rotors go up by the whole first-period change, r / rate = 30000 / 100 = 300 rad/s.
  // The interior point (the default algorithm) stops 4e-5 rad/s inside the active bound (measured), so 1e-4.
  const double first_change = p.params.max_omega_rate_rad_s2 / p.params.rate_hz;
  const double at_bound_rad_s = 1e-4;
  EXPECT_NEAR(up.first_command_rad_s(0), p.hover_rad_s + first_change, at_bound_rad_s);
  EXPECT_NEAR(up.first_command_rad_s(1), p.hover_rad_s + first_change, at_bound_rad_s);
  for (int k = 2; k <= p.params.horizon_steps; ++k) {
    const MpcState s = qp.PredictedState(k);
    EXPECT_LE(s(kMpcOmega1), 1200.0 + 0.05);
  }
  // 5 m down: the commands may not go below 0.
  MpcQp qp_down(p.params, kMpcInputSize, 1200.0, MpcController::TerminalWeight(p.model, p.params));
  const MpcQpSolution down = qp_down.Solve(p.Data(p.HoverState(), Eigen::Vector2d(0.0, -5.0), last));
  ASSERT_EQ(down.status, MpcSolveStatus::kSolved);
  EXPECT_NEAR(down.first_command_rad_s(0), p.hover_rad_s - first_change, at_bound_rad_s);
}

TEST(MpcQpTest, TiltLimitHeldWithinTheSlack) {
  Problem p;
  MpcQp qp(p.params, kMpcInputSize, 1200.0, MpcController::TerminalWeight(p.model, p.params));
  const MpcQpSolution sol =
      qp.Solve(p.Data(p.HoverState(), Eigen::Vector2d(4.0, 0.0), Eigen::Vector2d::Constant(p.hover_rad_s)));
  ASSERT_EQ(sol.status, MpcSolveStatus::kSolved);
  double peak = 0.0;
  for (int k = 1; k <= p.params.horizon_steps; ++k) peak = std::max(peak, std::fabs(qp.PredictedState(k)(kMpcPhi)));
  // 4 m sideways asks for the largest tilt: the plan reaches the limit and stays within it plus the
  // slack at the checked (even) steps; an odd step between two may pass it by what 20 ms of pitch
  // rate add (measured 0.0034 rad).
  EXPECT_LE(peak, p.params.max_tilt_rad + sol.tilt_slack_rad + 0.005);
  EXPECT_GT(peak, 0.5 * p.params.max_tilt_rad);
  // Starting past the limit (0.7 rad) the hard limit would be infeasible; the soft one solves.
  MpcState tilted = p.HoverState();
  tilted(kMpcPhi) = 0.7;
  MpcQp qp2(p.params, kMpcInputSize, 1200.0, MpcController::TerminalWeight(p.model, p.params));
  const MpcQpSolution past =
      qp2.Solve(p.Data(tilted, Eigen::Vector2d::Zero(), Eigen::Vector2d::Constant(p.hover_rad_s)));
  ASSERT_EQ(past.status, MpcSolveStatus::kSolved);
  EXPECT_GT(past.tilt_slack_rad, 0.1);
}

// The three alglib algorithms on random states and references: the first
// commands agree (each solves the same convex QP).
TEST(MpcQpTest, AlgorithmsAgreeOnRandomProblems) {
  Problem p;
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  MpcParams bleic = p.params, aul = p.params;
  bleic.algorithm = MpcQpAlgorithm::kBleic;
  bleic.max_iterations = 0;
  bleic.solver_tolerance = 1e-9;
  aul.algorithm = MpcQpAlgorithm::kDenseAul;
  aul.solver_tolerance = 1e-9;
  const MultiArmMpcStateMatrix P = MpcController::TerminalWeight(p.model, p.params);
  for (int trial = 0; trial < 10; ++trial) {
    MpcState s0 = p.HoverState();
    s0(kMpcPhi) = 0.3 * unit(rng);
    s0(kMpcXDot) = unit(rng);
    s0(kMpcZDot) = unit(rng);
    s0(kMpcPhiDot) = unit(rng);
    s0(kMpcOmega1) += 150.0 * unit(rng);
    s0(kMpcOmega2) += 150.0 * unit(rng);
    const Eigen::Vector2d target(unit(rng), unit(rng));
    const Eigen::Vector2d last = s0.tail<2>();
    MpcQp a(p.params, kMpcInputSize, 1200.0, P), b(bleic, kMpcInputSize, 1200.0, P), c(aul, kMpcInputSize, 1200.0, P);
    const MpcQpData data = p.Data(s0, target, last);
    const MpcQpSolution sa = a.Solve(data), sb = b.Solve(data), sc = c.Solve(data);
    ASSERT_EQ(sa.status, MpcSolveStatus::kSolved);
    ASSERT_EQ(sb.status, MpcSolveStatus::kSolved);
    ASSERT_EQ(sc.status, MpcSolveStatus::kSolved);
    EXPECT_NEAR(sa.first_command_rad_s(0), sb.first_command_rad_s(0), 1.0) << trial;
    EXPECT_NEAR(sa.first_command_rad_s(1), sb.first_command_rad_s(1), 1.0) << trial;
    EXPECT_NEAR(sa.first_command_rad_s(0), sc.first_command_rad_s(0), 1.0) << trial;
    EXPECT_NEAR(sa.first_command_rad_s(1), sc.first_command_rad_s(1), 1.0) << trial;
  }
}

}  // namespace
}  // namespace birotor
