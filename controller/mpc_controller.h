// The model predictive controller as a pure library (no LCM, no logging):
// each period it linearises the prediction model (controller/mpc_model.h)
// about the current state and the command in force, extrapolates the
// reference over the horizon with its velocity and acceleration, solves the
// condensed QP (controller/mpc_qp.h, the one QP of every vehicle, at N = 2) and checks the answer. A solve that
// fails, comes late (past the deadline) or returns a non-finite or infeasible
// answer is reported as such: the caller flies the cascade for that period.
// It also keeps what the vehicle does not report to the controller: the rotor
// speeds (the motor lag run on the commands sent) and a constant acceleration
// disturbance (offset-free tracking).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "controller/mpc_model.h"
#include "controller/mpc_params.h"
#include "controller/mpc_qp.h"
#include "controller/position_attitude_law.h"
#include "controller/reference_point.h"
#include "model/birotor_params.h"

namespace birotor {

struct MpcPlanInput {
  BodyState state;                                               // body state (the controller's observer)
  ReferencePoint reference;                                      // reference now (extrapolated inside)
  Eigen::Vector2d thrust_scale = Eigen::Vector2d::Ones();        // rotor efficiencies for the prediction [1]
  Eigen::Vector2d last_command_rad_s = Eigen::Vector2d::Zero();  // the command in force until now
  double period_s = 0.01;                                        // time to the next solve [s]
  // The hover-infeasible descent: plan with the descent's state weights
  // (MpcParams descent_*), level and calm first (docs/mpc.md, 70 % loss).
  bool level_descent = false;
};

enum class MpcOutcome : int {
  kSolved = 0,
  kSolverFailed = 1,
  kNonFinite = 2,
  kInfeasible = 3,
  kLate = 4,  // solved, but after the deadline
};

struct MpcPlan {
  MpcOutcome outcome = MpcOutcome::kSolverFailed;
  Eigen::Vector2d omega_cmd_rad_s = Eigen::Vector2d::Zero();  // valid when outcome is kSolved
  int iterations = 0;
  double solve_time_s = 0.0;    // linearise, condense, solve, check [s]
  double tilt_slack_rad = 0.0;  // how far the plan exceeds the tilt limit [rad]
};

// Counters and solve-time figures since start-up (times: over the last
// kMpcTimeWindow solves; the maximum over all of them).
struct MpcStats {
  int64_t solves = 0;
  int64_t solver_failed = 0;
  int64_t non_finite = 0;
  int64_t infeasible = 0;
  int64_t late = 0;
  int64_t recoveries = 0;  // sudden pitch disturbances taken (recovery weights started)
  int32_t last_iterations = 0;
  int32_t max_iterations = 0;
  double solve_p50_s = 0.0;
  double solve_p99_s = 0.0;
  double solve_max_s = 0.0;
  int64_t Fallbacks() const { return solver_failed + non_finite + infeasible + late; }
};
constexpr int kMpcTimeWindow = 4096;

// The solve times CONTROLLER_STATUS reports, for both MPCs (MpcController
// and the N-rotor node's MultiArmMpc): the last kMpcTimeWindow solve times
// on the deadline's clock and the maximum since start-up. No allocation.
class MpcSolveTimes {
 public:
  void Record(double solve_time_s);
  // solve_p50_s, solve_p99_s (over the window) and solve_max_s of *stats;
  // left as they are before the first solve.
  void Fill(MpcStats* stats) const;

 private:
  std::array<double, kMpcTimeWindow> times_s_{};
  mutable std::array<double, kMpcTimeWindow> scratch_{};  // Percentile reorders: a copy
  int64_t recorded_ = 0;
  double max_s_ = 0.0;
};

// What one period of mode mpc sends (MpcController::Fly).
struct MpcPeriod {
  // Finite, within [0, omega_max] and within max_omega_rate_rad_s2 * period_s
  // of the last command (except the first command in flight, see Fly).
  Eigen::Vector2d omega_cmd_rad_s = Eigen::Vector2d::Zero();
  bool planned = false;    // a solve was attempted
  bool fell_back = false;  // it failed, was late or bad: the cascade's command was sent
  MpcPlan plan;            // the attempt (when planned)
};

class MpcController {
 public:
  MpcController(const BirotorParams& vehicle, const MpcParams& params);

  // One solve. Does not change the rotor-speed estimate (Advance does).
  MpcPlan Plan(const MpcPlanInput& input);
  // After every command sent (the MPC's or the fallback's), held for dt_s [s]:
  // runs the motor lag on it (model/plant.h MotorStep).
  void Advance(const Eigen::Vector2d& omega_cmd_rad_s, double dt_s);

  // One period of mode mpc: Plan (when attempt; the caller does not attempt
  // in its controlled descent), the plan's first command if it solved in
  // time, else cascade_rad_s (the fallback, counted in Stats); either is
  // rate-limited against input.last_command_rad_s and clamped to
  // [0, omega_max]. The first period in flight plans from the rotor speeds
  // the motor model believes in, not from the zero commands sent before the
  // first POSE, and its command is the only one exempt from the rate limit.
  MpcPeriod Fly(MpcPlanInput input, const Eigen::Vector2d& cascade_rad_s, bool attempt);

  // Statistics; fills the percentiles (copies the window, no allocation).
  MpcStats Stats() const;
  const Eigen::Vector3d& disturbance() const { return disturbance_; }
  const Eigen::Vector2d& rotor_speed_estimate_rad_s() const { return omega_estimate_rad_s_; }
  const MpcParams& params() const { return params_; }
  const MpcQp& qp() const { return qp_; }

  // The terminal weight P: MpcQp::TerminalWeight on the hover model's step
  // (the cost-to-go of an unconstrained LQR with the stage weights).
  static MultiArmMpcStateMatrix TerminalWeight(const MpcPredictionModel& model, const MpcParams& params);

 private:
  void UpdateDisturbance(const MpcState& now);
  void RebaseDisturbance(const MpcState& now, const Eigen::Vector2d& command_rad_s, const MpcModelContext& context);
  void FillReference(const MpcPlanInput& input, const Eigen::Vector2d& feed_forward_rad_s);
  void Record(const MpcPlan& plan);

  BirotorParams vehicle_;
  MpcParams params_;
  MpcPredictionModel model_;
  MpcQp qp_;
  MpcQpData data_;
  Eigen::Vector2d omega_estimate_rad_s_;
  Eigen::Vector3d disturbance_ = Eigen::Vector3d::Zero();
  // The previous solve's state and context, and what has been sent since.
  bool has_previous_ = false;
  MpcState previous_state_ = MpcState::Zero();
  MpcModelContext previous_context_;
  Eigen::Vector2d sent_since_previous_ = Eigen::Vector2d::Zero();
  double elapsed_since_previous_s_ = 0.0;
  int advances_since_previous_ = 0;
  double recovery_left_s_ = 0.0;  // recovery weights this much longer [s]
  bool flown_ = false;            // Fly has sent a command

  MpcStats stats_;
  MpcSolveTimes solve_times_;
};

}  // namespace birotor
