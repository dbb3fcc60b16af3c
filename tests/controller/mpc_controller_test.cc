// The model predictive controller closed around its own prediction model
// (the arms rigid, no sensors): it reaches a step, holds a weak rotor level
// when it knows the rotor's efficiency, learns a constant disturbance, and
// reports late solves and its solve-time statistics.
#include "controller/mpc_controller.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace birotor {
namespace {

struct LoopResult {
  MpcState final_state;
  double peak_tilt_rad = 0.0;
  double max_command_rad_s = 0.0;
  double max_command_change_rad_s = 0.0;
  double peak_pitch_rate_rad_s = 0.0;  // |phi_dot| after the first 0.1 s
  int64_t fallbacks = 0;
};

// A rotor losing thrust during the flight: from at_s the plant flies with
// scale_after, the controller plans with it from at_s + known_after_s (as
// FORCE reports it, ~15 ms later).
struct RotorLoss {
  double at_s = 1e9;
  Eigen::Vector2d scale_after = Eigen::Vector2d::Ones();
  double known_after_s = 0.0;
};

// Flies for duration_s: the plant is the prediction model stepped at 1 ms
// with the true thrust scales and disturbance; the controller plans with
// planned_scale. level_descent: the hover-infeasible descent as
// VehicleController asks for it (at the current position, sinking at 0.3 m/s).
// Peak tilt and pitch rate count from the loss when there is one.
LoopResult Fly(MpcController* mpc, const Eigen::Vector2d& target_m, const Eigen::Vector2d& true_scale,
               Eigen::Vector2d planned_scale, const Eigen::Vector3d& true_disturbance, double duration_s,
               bool level_descent = false, const RotorLoss& loss = RotorLoss()) {
  const MpcPredictionModel plant{BirotorParams()};
  MpcModelContext truth;
  truth.thrust_scale = true_scale;
  truth.disturbance = true_disturbance;
  MpcState s = MpcState::Zero();
  s(kMpcOmega1) = s(kMpcOmega2) = mpc->rotor_speed_estimate_rad_s()(0);
  const double period = 1.0 / mpc->params().rate_hz;
  Eigen::Vector2d command = s.tail<2>();
  LoopResult out;
  for (int step = 0; step * period < duration_s; ++step) {
    const double t_s = step * period;
    if (t_s >= loss.at_s) truth.thrust_scale = loss.scale_after;
    if (t_s >= loss.at_s + loss.known_after_s) planned_scale = loss.scale_after;
    MpcPlanInput in;
    in.state.position_m = s.head<2>();
    in.state.phi_rad = s(kMpcPhi);
    in.state.velocity_m_s = s.segment<2>(kMpcXDot);
    in.state.phi_dot_rad_s = s(kMpcPhiDot);
    in.reference.position_m = target_m;
    if (level_descent) {
      in.reference.position_m = s.head<2>();
      in.reference.velocity_m_s = Eigen::Vector2d(0.0, -0.3);
      in.level_descent = true;
    }
    in.thrust_scale = planned_scale;
    in.last_command_rad_s = command;
    in.period_s = period;
    const MpcPlan plan = mpc->Plan(in);
    Eigen::Vector2d next = command;
    if (plan.outcome == MpcOutcome::kSolved)
      next = plan.omega_cmd_rad_s;
    else
      ++out.fallbacks;
    out.max_command_change_rad_s = std::max(out.max_command_change_rad_s, (next - command).cwiseAbs().maxCoeff());
    out.max_command_rad_s = std::max(out.max_command_rad_s, next.maxCoeff());
    command = next;
    for (int i = 0; i < 10; ++i) s = plant.Step(s, command, truth, period / 10.0);
    mpc->Advance(command, period);
    if (loss.at_s < 1e9 && t_s < loss.at_s) continue;
    out.peak_tilt_rad = std::max(out.peak_tilt_rad, std::fabs(s(kMpcPhi)));
    if (step * period >= 0.1) out.peak_pitch_rate_rad_s = std::max(out.peak_pitch_rate_rad_s, std::fabs(s(kMpcPhiDot)));
  }
  out.final_state = s;
  return out;
}

TEST(MpcControllerTest, ReachesAStepWithinTheLimits) {
  MpcParams params;
  params.deadline_s = 10.0;  // no timing in unit tests: only failed or bad answers count here
  MpcController mpc(BirotorParams(), params);
  const LoopResult r = Fly(&mpc, Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d::Ones(), Eigen::Vector2d::Ones(),
                           Eigen::Vector3d::Zero(), 5.0);
  std::printf("step: final %.4f %.4f tilt %.3f max cmd %.1f change %.1f fallbacks %ld\n", r.final_state(0),
              r.final_state(1), r.peak_tilt_rad, r.max_command_rad_s, r.max_command_change_rad_s, r.fallbacks);
  // 5 s: position weight 3e3 / velocity 1e3 (mpc_params.h) reach a 0.5 m step
  // more slowly than 1e5 / 3e3 did (0.4965 m after 3 s); measured 1e-4 at 5 s.
  EXPECT_NEAR(r.final_state(kMpcX), 0.5, 2e-4);
  EXPECT_NEAR(r.final_state(kMpcZ), 0.5, 2e-4);
  EXPECT_LE(r.max_command_rad_s, 1200.0);
  EXPECT_LE(r.max_command_change_rad_s, params.max_omega_rate_rad_s2 / params.rate_hz + 1e-9);
  EXPECT_EQ(r.fallbacks, 0);
  EXPECT_EQ(mpc.Stats().recoveries, 0);  // a step is no sudden disturbance
}

TEST(MpcControllerTest, WeakRotorKnownAndDisturbanceLearned) {
  MpcParams params;
  params.deadline_s = 10.0;
  MpcController mpc(BirotorParams(), params);
  const Eigen::Vector2d weak(1.0, 0.6);
  const LoopResult r = Fly(&mpc, Eigen::Vector2d::Zero(), weak, weak, Eigen::Vector3d(0.5, -0.5, 2.0), 5.0);
  std::printf("weak: final %.4f %.4f tilt %.3f d %.3f %.3f %.3f\n", r.final_state(0), r.final_state(1), r.peak_tilt_rad,
              mpc.disturbance()(0), mpc.disturbance()(1), mpc.disturbance()(2));
  EXPECT_NEAR(mpc.disturbance()(0), 0.5, 1e-3);  // measured < 5e-4
  EXPECT_NEAR(mpc.disturbance()(1), -0.5, 1e-3);
  EXPECT_NEAR(mpc.disturbance()(2), 2.0, 5e-3);
  EXPECT_NEAR(r.final_state(kMpcX), 0.0, 0.0045);  // measured -0.0030
  EXPECT_NEAR(r.final_state(kMpcZ), 0.0, 1e-3);
}

TEST(MpcControllerTest, InfeasibleDescentIsLevelAndCalmWithTheDescentWeights) {
  // Rotor 2 at 30 % (a 70 % loss), known: hover is infeasible, the sink-rate
  // reference cannot be flown. With the tracking weights the plan pulses the
  // strong rotor for vertical impulse and the pitch swings; with the descent
  // weights (mpc_params.h) it stays level and calm. docs/mpc.md.
  const Eigen::Vector2d weak(1.0, 0.3);
  MpcParams tracking;
  tracking.deadline_s = 10.0;
  tracking.descent_position_weight_1_m2 = tracking.position_weight_1_m2;
  tracking.descent_velocity_weight_s2_m2 = tracking.velocity_weight_s2_m2;
  tracking.descent_tilt_weight_1_rad2 = tracking.tilt_weight_1_rad2;
  tracking.descent_pitch_rate_weight_s2_rad2 = tracking.pitch_rate_weight_s2_rad2;
  MpcController swinging(BirotorParams(), tracking);
  const LoopResult a = Fly(&swinging, Eigen::Vector2d::Zero(), weak, weak, Eigen::Vector3d::Zero(), 0.6, true);
  MpcParams params;
  params.deadline_s = 10.0;
  MpcController calm(BirotorParams(), params);
  const LoopResult b = Fly(&calm, Eigen::Vector2d::Zero(), weak, weak, Eigen::Vector3d::Zero(), 0.6, true);
  std::printf(
      "descent: tracking weights tilt %.4f rate %.3f sink %.3f; descent weights tilt %.4f rate %.3f sink %.3f\n",
      a.peak_tilt_rad, a.peak_pitch_rate_rad_s, a.final_state(kMpcZDot), b.peak_tilt_rad, b.peak_pitch_rate_rad_s,
      b.final_state(kMpcZDot));
  // Measured (0.6 s at 200 Hz): tracking weights peak tilt 0.0347 rad, pitch
  // rate 0.901 rad/s after the first 0.1 s; descent weights 0.0213 and 0.380
  // (ratios 0.61 and 0.42); both sink at 0.937 m/s (level costs no vertical
  // speed).
  EXPECT_LT(b.peak_tilt_rad, 1.5 * 0.0213);
  EXPECT_LT(b.peak_pitch_rate_rad_s, 1.5 * 0.380);
  EXPECT_LT(b.peak_pitch_rate_rad_s, 0.6 * a.peak_pitch_rate_rad_s);
  EXPECT_LT(b.peak_tilt_rad, 0.7 * a.peak_tilt_rad);
  EXPECT_NEAR(b.final_state(kMpcZDot), a.final_state(kMpcZDot), 0.01);
  EXPECT_EQ(a.fallbacks + b.fallbacks, 0);
}

TEST(MpcControllerTest, RotorLossTakenAtOnceAndRecoveredAttitudeFirst) {
  // Hover, then rotor 2 loses 40 % at 1 s; the controller learns the new
  // efficiency 15 ms later (as from FORCE). Without the disturbance step the
  // lost torque is low-passed and the tracking weights trade tilt for
  // altitude; with it (mpc_params.h defaults) the first solve after the loss
  // takes the pitch disturbance at once and the recovery weights hold the
  // attitude first.
  RotorLoss loss;
  loss.at_s = 1.0;
  loss.scale_after = Eigen::Vector2d(1.0, 0.6);
  loss.known_after_s = 0.015;
  MpcParams off;
  off.deadline_s = 10.0;
  off.disturbance_pitch_step_rad_s2 = 0.0;
  MpcController slow(BirotorParams(), off);
  const LoopResult a = Fly(&slow, Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), Eigen::Vector2d::Ones(),
                           Eigen::Vector3d::Zero(), 2.0, false, loss);
  MpcParams params;
  params.deadline_s = 10.0;
  MpcController fast(BirotorParams(), params);
  const LoopResult b = Fly(&fast, Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), Eigen::Vector2d::Ones(),
                           Eigen::Vector3d::Zero(), 2.0, false, loss);
  std::printf("loss: step off tilt %.4f recoveries %ld; step on tilt %.4f recoveries %ld\n", a.peak_tilt_rad,
              slow.Stats().recoveries, b.peak_tilt_rad, fast.Stats().recoveries);
  EXPECT_EQ(slow.Stats().recoveries, 0);
  EXPECT_EQ(fast.Stats().recoveries, 1);
  // Measured: 0.0242 rad without the step, 0.0117 with it (0.48x).
  EXPECT_LT(b.peak_tilt_rad, 0.7 * a.peak_tilt_rad);
  EXPECT_LT(b.peak_tilt_rad, 1.5 * 0.0117);
  EXPECT_EQ(a.fallbacks + b.fallbacks, 0);
}

TEST(MpcControllerTest, LateSolvesAreCountedAndTimed) {
  MpcParams params;
  params.deadline_s = 0.0;                    // every solve is late
  params.algorithm = MpcQpAlgorithm::kBleic;  // reports its iterations
  MpcController mpc(BirotorParams(), params);
  const LoopResult r = Fly(&mpc, Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), Eigen::Vector2d::Ones(),
                           Eigen::Vector3d::Zero(), 0.1);
  const MpcStats stats = mpc.Stats();
  EXPECT_EQ(stats.solves, 20);  // 0.1 s at 200 Hz
  EXPECT_EQ(stats.late, 20);
  EXPECT_EQ(stats.Fallbacks(), 20);
  EXPECT_EQ(r.fallbacks, 20);
  EXPECT_LE(stats.solve_p50_s, stats.solve_p99_s);
  EXPECT_LE(stats.solve_p99_s, stats.solve_max_s);
  EXPECT_GT(stats.max_iterations, 0);
}

}  // namespace
}  // namespace birotor
