// The condensed quadratic program of the model predictive controller, for any
// number N of rotor speed inputs (the birotor's MpcController at N = 2 and the
// N-rotor MultiArmMpc fly this one QP), and its solution with alglib's minqp
// (Debian's libalglib-dev). Over the horizon of one linearised step
// s+ = A s + B u + c (state 6 + N: controller/multi_arm_mpc_model.h):
//   S = Gamma E V + o,   o_k = A o_(k-1) + c (o_0 = s0),   Gamma_kj = A^(k-1-j) B,
// V = [v_0 .. v_(B-1)], v_b in R^N held over block b (move blocking,
// MpcParams::input_blocks). Cost
//   sum_(k=1..N-1) |s_k - r_k|_Q^2 + |s_N - r_N|_P^2 + sum_k |u_k - u_ff,k|_R^2
//   + sum_b |v_b - v_(b-1)|_Rd^2 (v_(-1) = the last command) + w eps^2
// (Q and P: those of MpcQpData::weights; R = input weight x I_N, Rd = input
// rate weight x I_N) over V and the tilt slack eps >= 0, subject to
//   0 <= v_b,i <= omega_max,   |v_0,i - v_(-1),i| <= r dt_command,
//   |v_b,i - v_(b-1),i| <= r dt_step,   -phi_max - eps <= phi_k <= phi_max + eps
// (phi at every tilt_check_every_steps-th step and the last). Variables N B + 1
// (11 for the birotor, 16 for the trirotor at B = 5). Matrices are sized once
// at construction; alglib itself allocates inside its solver (docs/mpc.md).
// Never throws: an alglib error is a failed solve.
#pragma once

#include <Eigen/Core>
#include <Eigen/Dense>
#include <algorithm>
#include <memory>
#include <vector>

#include "controller/mpc_params.h"
#include "controller/multi_arm_mpc_model.h"

namespace birotor {

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

// The terminal weight P of the QP: the discrete Riccati solution
//   P = Q + A^T P A - A^T P B (R + B^T P B)^-1 B^T P A,   R = input_weight I_N,
// iterated from P = Q to a fixed point (relative change below 1e-12): the
// cost-to-go of the unconstrained LQR beyond the horizon. Generic over the
// matrix types so the birotor's fixed-size step (controller/mpc_model.h) and
// the N-input step (multi_arm_mpc_model.h) each keep their own arithmetic
// (Eigen's fixed and dynamic products round differently in the last bit).
template <typename StateMatrix, typename InputMatrix>
StateMatrix MpcRiccatiTerminalWeight(const StateMatrix& a, const InputMatrix& b, const StateMatrix& q,
                                     double input_weight) {
  using InputSquare = Eigen::Matrix<double, InputMatrix::ColsAtCompileTime, InputMatrix::ColsAtCompileTime>;
  using Gain = Eigen::Matrix<double, InputMatrix::ColsAtCompileTime, StateMatrix::ColsAtCompileTime>;
  const InputSquare r = InputSquare::Identity(b.cols(), b.cols()) * input_weight;
  StateMatrix p = q;
  for (int i = 0; i < 5000; ++i) {
    const InputSquare s = r + b.transpose() * p * b;
    const Gain k = s.ldlt().solve(Gain(b.transpose() * p * a));
    StateMatrix next = q + a.transpose() * p * (a - b * k);
    next = 0.5 * (next + next.transpose());
    const double change = (next - p).norm() / std::max(1.0, p.norm());
    p = next;
    if (change < 1e-12) break;
  }
  return p;
}

// Which state weights a solve plans with (MpcParams: the tracking ones, the
// recovery_* ones after a sudden pitch disturbance, the descent_* ones in
// the hover-infeasible descent, the tilted_hover_* ones of a fully-actuated
// vehicle about a tilted hover, the birotor's steady_* pitch rate weight
// while its reference does not accelerate).
enum class MpcWeightSet : int { kTracking = 0, kRecovery = 1, kDescent = 2, kTiltedHover = 3, kSteady = 4 };
constexpr int kMpcWeightSets = 5;

// Everything one solve needs besides the options.
struct MpcQpData {
  MultiArmMpcState initial;                        // s0, 6 + N
  MultiArmMpcLinearStep step;                      // the one linearisation used for every step
  Eigen::MatrixXd reference;                       // (6 + N) x horizon: r_1 .. r_N (speeds: the feed-forward)
  Eigen::MatrixXd feed_forward_rad_s;              // N x horizon: u_ff,k of step k (0-based)
  MultiArmMpcInputs last_command_rad_s;            // u_(-1)
  double command_period_s = 0.005;                 // dt_command: time u_0 is held before the next solve [s]
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
  MultiArmMpcInputs first_command_rad_s;  // u_0, inside the box (valid when solved; zeros otherwise)
  double tilt_slack_rad = 0.0;            // eps
  int iterations = 0;                     // alglib's outer + inner iterations (DENSE-AUL: factorizations)
  int termination_type = 0;               // alglib's code
};

class MpcQp {
 public:
  // terminal_weight: P of every weight set until SetTerminalWeight.
  MpcQp(const MpcParams& params, int rotors, double omega_max_rad_s, const MultiArmMpcStateMatrix& terminal_weight);
  ~MpcQp();
  MpcQp(const MpcQp&) = delete;
  MpcQp& operator=(const MpcQp&) = delete;

  // The terminal weight of another weight set (WeightParams).
  void SetTerminalWeight(MpcWeightSet set, const MultiArmMpcStateMatrix& terminal_weight) {
    terminal_weight_[static_cast<int>(set)] = terminal_weight;
  }

  // Builds and solves; warm-starts from the previous plan shifted by one step.
  MpcQpSolution Solve(const MpcQpData& data);

  // The stage weight Q (diagonal, from the options): position, altitude
  // (altitude_weight_factor x position), velocity, tilt and pitch rate
  // weights; 0 on the rotor speeds (they are the inputs' business).
  static MultiArmMpcStateMatrix StageWeight(const MpcParams& params, int rotors);
  // The options with the state weights of `set` in place of the tracking ones.
  static MpcParams WeightParams(const MpcParams& params, MpcWeightSet set);
  // The terminal weight P of the linearised hover step with Q =
  // StageWeight(params) (MpcRiccatiTerminalWeight).
  static MultiArmMpcStateMatrix TerminalWeight(const MultiArmMpcLinearStep& hover_step, const MpcParams& params);

  // Predicted state k (1..N) of the last solve's answer (for tests and plots).
  MultiArmMpcState PredictedState(int k) const;
  // First prediction step of block b (0..B); block_start(B) = N.
  int block_start(int b) const { return block_start_[static_cast<size_t>(b)]; }
  int blocks() const { return blocks_; }
  int variables() const { return variables_; }
  int constraint_rows() const { return static_cast<int>(constraints_.rows()); }

 private:
  int InputIndex(int b, int rotor) const { return nu_ * b + rotor; }
  void Condense(const MpcQpData& data);
  void BuildCost(const MpcQpData& data);
  void BuildConstraints(const MpcQpData& data);
  MpcSolveStatus Check(const Eigen::VectorXd& x) const;
  void WarmStart(const MpcQpData& data);
  bool RunAlglib();

  MpcParams params_;
  double omega_max_rad_s_;
  int nu_;                                                  // rotors N
  int ns_;                                                  // states 6 + N
  int n_;                                                   // horizon steps
  int blocks_;                                              // input blocks B
  int variables_;                                           // N B + 1
  std::vector<int> block_start_;                            // B + 1 entries
  std::vector<int> tilt_steps_;                             // 0-based steps k (state s_(k+1)) with a tilt constraint
  MultiArmMpcStateMatrix stage_weight_[kMpcWeightSets];     // Q per weight set
  MultiArmMpcStateMatrix terminal_weight_[kMpcWeightSets];  // P per weight set
  Eigen::MatrixXd gamma_;                                   // ns N x nu N (per step)
  Eigen::MatrixXd gamma_blocked_;                           // ns N x nu B (per block)
  Eigen::VectorXd offset_;                                  // ns N
  Eigen::MatrixXd hessian_;                                 // variables x variables
  Eigen::VectorXd gradient_;
  Eigen::MatrixXd constraints_;  // rows x variables
  Eigen::VectorXd lower_, upper_;
  Eigen::VectorXd box_lower_, box_upper_;
  Eigen::MatrixXd weighted_;  // Qbar Gamma E, ns N x nu B
  Eigen::VectorXd error_;     // o - r, ns N
  Eigen::VectorXd start_;     // warm start
  Eigen::VectorXd solution_;  // the last accepted plan (warm start)
  Eigen::VectorXd last_x_;    // the last answer, accepted or not
  bool has_solution_ = false;
  struct Alglib;  // alglib's state and arrays (keeps ap.h out of this header)
  std::unique_ptr<Alglib> alglib_;
};

}  // namespace birotor
