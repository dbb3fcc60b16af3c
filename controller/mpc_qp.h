// The condensed quadratic program of the model predictive controller and its
// solution with alglib's minqp (Debian's libalglib-dev). Over N steps of one
// linearised step s+ = A s + B u + c the predicted states are
//   S = Gamma U + o,   o_k = A o_(k-1) + c (o_0 = s0),   Gamma_kj = A^(k-1-j) B,
// with U = E V: the step inputs are the B block inputs V = [v_0 .. v_(B-1)]
// held over their blocks (move blocking, MpcParams::input_blocks). The cost is
//   sum_(k=1..N-1) |s_k - r_k|_Q^2 + |s_N - r_N|_P^2 + sum_k |u_k - u_ff|_R^2
//   + sum_b |v_b - v_(b-1)|_Rd^2 (v_(-1) = the last command) + w eps^2
// (Q and P: those of MpcQpData::weights)
// over V and the tilt slack eps >= 0, subject to
//   0 <= v_b <= omega_max,   |v_0 - v_(-1)| <= r dt_command,
//   |v_b - v_(b-1)| <= r dt_step,   -phi_max - eps <= phi_k <= phi_max + eps
// (phi at every tilt_check_every_steps-th step and the last).
// Matrices are sized once at construction; alglib itself allocates inside its
// solver (said in docs/mpc.md). Never throws: an alglib error is a failed solve.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "controller/mpc_model.h"
#include "controller/mpc_params.h"

namespace birotor {

// Which state weights a solve plans with (MpcParams: the tracking ones, the
// recovery_* ones after a sudden pitch disturbance, the descent_* ones in
// the hover-infeasible descent).
// Tolerance of the answer check: alglib's interior point stops a little
// inside or outside a bound; anything beyond this is an infeasible answer.
inline constexpr double kMpcBoundToleranceRadS = 0.05;
inline constexpr double kMpcSlackScaleRad = 0.1;     // typical tilt excess, for alglib's variable scaling
inline constexpr double kMpcInputScaleRadS = 100.0;  // typical command change, for alglib's variable scaling

// Move blocking: the first prediction step of each of `blocks` blocks (clamped
// to [1, steps]) and the end, B + 1 entries: block b starts at
// round(N (b / B)^2), each at least one step after the last.
std::vector<int> MpcBlockStarts(int steps, int blocks);
// The 0-based steps k (state s_(k+1)) with a tilt constraint: every `every`-th
// step and the last.
std::vector<int> MpcTiltSteps(int steps, int every);

enum class MpcWeightSet : int { kTracking = 0, kRecovery = 1, kDescent = 2 };
constexpr int kMpcWeightSets = 3;

// Everything one solve needs besides the options.
struct MpcQpData {
  MpcState initial;                                              // s0
  MpcLinearStep step;                                            // the one linearisation used for every step
  Eigen::MatrixXd reference;                                     // 8 x N: r_1 .. r_N (speeds: the feed-forward)
  Eigen::Vector2d feed_forward_rad_s = Eigen::Vector2d::Zero();  // u_ff
  Eigen::Vector2d last_command_rad_s = Eigen::Vector2d::Zero();  // u_(-1)
  double command_period_s = 0.01;                  // dt_command: time u_0 is held before the next solve [s]
  MpcWeightSet weights = MpcWeightSet::kTracking;  // state weights of this solve (MpcQp::WeightParams)
};

enum class MpcSolveStatus : int {
  kSolved = 0,
  kSolverFailed = 1,  // alglib error or non-positive termination code
  kNonFinite = 2,     // NaN or inf in the answer
  kInfeasible = 3,    // the answer violates a bound or a rate limit beyond tolerance
};

struct MpcQpSolution {
  MpcSolveStatus status = MpcSolveStatus::kSolverFailed;
  Eigen::Vector2d first_command_rad_s = Eigen::Vector2d::Zero();  // u_0, inside the box
  double tilt_slack_rad = 0.0;                                    // eps
  int iterations = 0;        // alglib's outer + inner iterations (DENSE-AUL: factorizations)
  int termination_type = 0;  // alglib's code
};

class MpcQp {
 public:
  MpcQp(const MpcParams& params, double omega_max_rad_s, const MpcStateMatrix& terminal_weight);
  ~MpcQp();
  MpcQp(const MpcQp&) = delete;
  MpcQp& operator=(const MpcQp&) = delete;

  // The terminal weight of another weight set (WeightParams); until set,
  // that set plans with the terminal weight given above.
  void SetTerminalWeight(MpcWeightSet set, const MpcStateMatrix& terminal_weight) {
    terminal_weight_[static_cast<int>(set)] = terminal_weight;
  }

  // Builds and solves; warm-starts from the previous plan shifted by one step.
  MpcQpSolution Solve(const MpcQpData& data);

  // The stage weight Q (diagonal, from the options).
  static MpcStateMatrix StageWeight(const MpcParams& params);
  // The options with the state weights of `set` in place of the tracking ones.
  static MpcParams WeightParams(const MpcParams& params, MpcWeightSet set);

  // Predicted state k (1..N) of the last solve (for tests and plots).
  MpcState PredictedState(int k) const;
  // First prediction step of block b (0..B); block_start(B) = N.
  int block_start(int b) const { return block_start_[static_cast<size_t>(b)]; }
  int blocks() const { return blocks_; }

 private:
  void Condense(const MpcQpData& data);
  void BuildCost(const MpcQpData& data);
  void BuildConstraints(const MpcQpData& data);
  MpcSolveStatus Check(const Eigen::VectorXd& x) const;
  void WarmStart(const MpcQpData& data);

  MpcParams params_;
  double omega_max_rad_s_;
  int n_;                                           // horizon steps
  int blocks_;                                      // input blocks B
  int variables_;                                   // 2 B + 1
  std::vector<int> block_start_;                    // B + 1 entries
  std::vector<int> tilt_steps_;                     // 0-based steps k (state s_(k+1)) with a tilt constraint
  MpcStateMatrix stage_weight_[kMpcWeightSets];     // Q per weight set
  MpcStateMatrix terminal_weight_[kMpcWeightSets];  // P per weight set
  Eigen::MatrixXd gamma_;                           // 8N x 2N (per step)
  Eigen::MatrixXd gamma_blocked_;                   // 8N x 2B (per block)
  Eigen::VectorXd offset_;                          // 8N
  Eigen::MatrixXd hessian_;                         // variables x variables
  Eigen::VectorXd gradient_;
  Eigen::MatrixXd constraints_;  // rows x variables
  Eigen::VectorXd lower_, upper_;
  Eigen::VectorXd box_lower_, box_upper_;
  Eigen::MatrixXd weighted_;  // Qbar Gamma E, 8N x 2B
  Eigen::VectorXd error_;     // o - r, 8N
  Eigen::VectorXd start_;     // warm start
  Eigen::VectorXd solution_;  // the last accepted plan (warm start)
  Eigen::VectorXd last_x_;    // the last answer, accepted or not
  bool has_solution_ = false;
  struct Alglib;  // alglib's state and arrays (keeps ap.h out of this header)
  std::unique_ptr<Alglib> alglib_;
};

}  // namespace birotor
