// The condensed quadratic program of the N-input model predictive controller:
// controller/mpc_qp.h's problem with N rotor speed commands per step instead
// of two (one decision per rotor and block, the same cost, bounds, rate
// limits, soft tilt limit and alglib minqp solve). Over the horizon of one
// linearised step s+ = A s + B u + c:
//   S = Gamma E V + o,   o_k = A o_(k-1) + c (o_0 = s0),   Gamma_kj = A^(k-1-j) B,
// V = [v_0 .. v_(B-1)], v_b in R^N held over block b (move blocking). Cost
//   sum_(k=1..N-1) |s_k - r_k|_Q^2 + |s_N - r_N|_P^2 + sum_k |u_k - u_ff,k|_R^2
//   + sum_b |v_b - v_(b-1)|_Rd^2 (v_(-1) = the last command) + w eps^2
// over V and the tilt slack eps >= 0, subject to
//   0 <= v_b,i <= omega_max,   |v_0,i - v_(-1),i| <= r dt_command,
//   |v_b,i - v_(b-1),i| <= r dt_step,   -phi_max - eps <= phi_k <= phi_max + eps
// (phi at every tilt_check_every_steps-th step and the last). R = input weight
// x I_N and Rd = input rate weight x I_N: the per-rotor weights of MpcParams
// apply to every rotor. Variables N B + 1 (16 for the trirotor at B = 5).
// Matrices are sized once at construction; alglib itself allocates inside its
// solver (docs/mpc.md). Never throws: an alglib error is a failed solve.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "controller/mpc_params.h"
#include "controller/mpc_qp.h"
#include "controller/multi_arm_mpc_model.h"

namespace birotor {

// Everything one solve needs besides the options.
struct MultiArmMpcQpData {
  MultiArmMpcState initial;              // s0
  MultiArmMpcLinearStep step;            // the one linearisation used for every step
  Eigen::MatrixXd reference;             // (6 + N) x horizon: r_1 .. r_N
  Eigen::MatrixXd feed_forward_rad_s;    // N x horizon: u_ff,k of step k (0-based)
  MultiArmMpcInputs last_command_rad_s;  // u_(-1)
  double command_period_s = 0.005;       // dt_command: time u_0 is held before the next solve [s]
};

struct MultiArmMpcQpSolution {
  MpcSolveStatus status = MpcSolveStatus::kSolverFailed;
  MultiArmMpcInputs first_command_rad_s;  // u_0, inside the box (valid when solved)
  double tilt_slack_rad = 0.0;            // eps
  int iterations = 0;                     // alglib's outer + inner iterations (DENSE-AUL: factorizations)
  int termination_type = 0;               // alglib's code
};

class MultiArmMpcQp {
 public:
  MultiArmMpcQp(const MpcParams& params, int rotors, double omega_max_rad_s,
                const MultiArmMpcStateMatrix& terminal_weight);
  ~MultiArmMpcQp();
  MultiArmMpcQp(const MultiArmMpcQp&) = delete;
  MultiArmMpcQp& operator=(const MultiArmMpcQp&) = delete;

  // Builds and solves; warm-starts from the previous plan shifted by one step.
  MultiArmMpcQpSolution Solve(const MultiArmMpcQpData& data);

  // The stage weight Q (diagonal): MpcQp::StageWeight's body weights, 0 on
  // the rotor speeds (they are the inputs' business).
  static MultiArmMpcStateMatrix StageWeight(const MpcParams& params, int rotors);

  int variables() const { return variables_; }
  int blocks() const { return blocks_; }
  int constraint_rows() const { return static_cast<int>(constraints_.rows()); }

 private:
  int InputIndex(int b, int rotor) const { return nu_ * b + rotor; }
  int block_start(int b) const { return block_start_[static_cast<size_t>(b)]; }
  void Condense(const MultiArmMpcQpData& data);
  void BuildCost(const MultiArmMpcQpData& data);
  void BuildConstraints(const MultiArmMpcQpData& data);
  MpcSolveStatus Check(const Eigen::VectorXd& x) const;
  void WarmStart(const MultiArmMpcQpData& data);
  bool RunAlglib();

  MpcParams params_;
  double omega_max_rad_s_;
  int nu_;                        // rotors N
  int ns_;                        // states 6 + N
  int n_;                         // horizon steps
  int blocks_;                    // input blocks B
  int variables_;                 // N B + 1
  std::vector<int> block_start_;  // B + 1 entries
  std::vector<int> tilt_steps_;   // 0-based steps k (state s_(k+1)) with a tilt constraint
  MultiArmMpcStateMatrix stage_weight_;
  MultiArmMpcStateMatrix terminal_weight_;
  Eigen::MatrixXd gamma_;          // ns N x nu N (per step)
  Eigen::MatrixXd gamma_blocked_;  // ns N x nu B (per block)
  Eigen::VectorXd offset_;         // ns N
  Eigen::MatrixXd hessian_;        // variables x variables
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
