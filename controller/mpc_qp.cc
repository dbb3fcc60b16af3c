#include "controller/mpc_qp.h"

#include <libalglib/optimization.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace birotor {

std::vector<int> MpcBlockStarts(int steps, int blocks) {
  blocks = std::clamp(blocks, 1, steps);
  std::vector<int> starts(static_cast<size_t>(blocks) + 1);
  starts[0] = 0;
  for (int b = 1; b <= blocks; ++b) {
    const double fraction = static_cast<double>(b) / blocks;
    const int at = static_cast<int>(std::lround(steps * fraction * fraction));
    // Leave room for the blocks still to come.
    starts[static_cast<size_t>(b)] = std::clamp(at, starts[static_cast<size_t>(b) - 1] + 1, steps - (blocks - b));
  }
  return starts;
}

std::vector<int> MpcTiltSteps(int steps, int every) {
  std::vector<int> out;
  for (int k = std::max(every, 1) - 1; k < steps; k += std::max(every, 1)) out.push_back(k);
  if (out.empty() || out.back() != steps - 1) out.push_back(steps - 1);
  return out;
}

struct MpcQp::Alglib {
  alglib::minqpstate state;
  alglib::minqpreport report;
  alglib::real_2d_array quadratic, constraints;
  alglib::real_1d_array linear, box_lower, box_upper, lower, upper, start, scale, x;
};

MultiArmMpcStateMatrix MpcQp::StageWeight(const MpcParams& params, int rotors) {
  MultiArmMpcState diagonal = MultiArmMpcState::Zero(kMpcBodyStates + rotors);
  diagonal(kMpcX) = params.position_weight_1_m2;
  diagonal(kMpcZ) = params.altitude_weight_factor * params.position_weight_1_m2;
  diagonal(kMpcXDot) = diagonal(kMpcZDot) = params.velocity_weight_s2_m2;
  diagonal(kMpcPhi) = params.tilt_weight_1_rad2;
  diagonal(kMpcPhiDot) = params.pitch_rate_weight_s2_rad2;
  return diagonal.asDiagonal();
}

MpcParams MpcQp::WeightParams(const MpcParams& params, MpcWeightSet set) {
  MpcParams out = params;
  if (set == MpcWeightSet::kRecovery) {
    out.position_weight_1_m2 = params.recovery_position_weight_1_m2;
    out.velocity_weight_s2_m2 = params.recovery_velocity_weight_s2_m2;
    out.tilt_weight_1_rad2 = params.recovery_tilt_weight_1_rad2;
    out.pitch_rate_weight_s2_rad2 = params.recovery_pitch_rate_weight_s2_rad2;
  } else if (set == MpcWeightSet::kDescent) {
    out.position_weight_1_m2 = params.descent_position_weight_1_m2;
    out.velocity_weight_s2_m2 = params.descent_velocity_weight_s2_m2;
    out.tilt_weight_1_rad2 = params.descent_tilt_weight_1_rad2;
    out.pitch_rate_weight_s2_rad2 = params.descent_pitch_rate_weight_s2_rad2;
  } else if (set == MpcWeightSet::kSteady) {
    out.pitch_rate_weight_s2_rad2 = params.steady_pitch_rate_weight_s2_rad2;
  } else if (set == MpcWeightSet::kTiltedHover) {
    out.tilt_weight_1_rad2 = params.tilted_hover_tilt_weight_1_rad2;
    out.pitch_rate_weight_s2_rad2 = params.tilted_hover_pitch_rate_weight_s2_rad2;
  }
  return out;
}

MultiArmMpcStateMatrix MpcQp::TerminalWeight(const MultiArmMpcLinearStep& hover_step, const MpcParams& params) {
  return MpcRiccatiTerminalWeight(hover_step.a, hover_step.b,
                                  StageWeight(params, static_cast<int>(hover_step.b.cols())),
                                  params.input_weight_s2_rad2);
}

MpcQp::MpcQp(const MpcParams& params, int rotors, double omega_max_rad_s, const MultiArmMpcStateMatrix& terminal_weight)
    : params_(params),
      omega_max_rad_s_(omega_max_rad_s),
      nu_(rotors),
      ns_(kMpcBodyStates + rotors),
      n_(params.horizon_steps),
      blocks_(std::clamp(params.input_blocks, 1, params.horizon_steps)),
      variables_(rotors * blocks_ + 1),
      block_start_(MpcBlockStarts(n_, blocks_)),
      tilt_steps_(MpcTiltSteps(n_, params.tilt_check_every_steps)),
      gamma_(Eigen::MatrixXd::Zero(ns_ * n_, nu_ * n_)),
      gamma_blocked_(Eigen::MatrixXd::Zero(ns_ * n_, nu_ * blocks_)),
      offset_(ns_ * n_),
      hessian_(variables_, variables_),
      gradient_(variables_),
      constraints_(Eigen::MatrixXd::Zero(nu_ * (blocks_ - 1) + 2 * static_cast<int>(tilt_steps_.size()), variables_)),
      lower_(constraints_.rows()),
      upper_(constraints_.rows()),
      box_lower_(variables_),
      box_upper_(variables_),
      weighted_(ns_ * n_, nu_ * blocks_),
      error_(ns_ * n_),
      start_(variables_),
      solution_(Eigen::VectorXd::Zero(variables_)),
      last_x_(Eigen::VectorXd::Zero(variables_)),
      alglib_(std::make_unique<Alglib>()) {
  for (int w = 0; w < kMpcWeightSets; ++w) {
    stage_weight_[w] = StageWeight(WeightParams(params, static_cast<MpcWeightSet>(w)), rotors);
    terminal_weight_[w] = terminal_weight;
  }
  Alglib& a = *alglib_;
  const int rows = static_cast<int>(constraints_.rows());
  a.quadratic.setlength(variables_, variables_);
  a.constraints.setlength(rows, variables_);
  a.linear.setlength(variables_);
  a.box_lower.setlength(variables_);
  a.box_upper.setlength(variables_);
  a.lower.setlength(rows);
  a.upper.setlength(rows);
  a.start.setlength(variables_);
  a.scale.setlength(variables_);
  for (int j = 0; j < variables_; ++j) a.scale[j] = (j == variables_ - 1) ? kMpcSlackScaleRad : kMpcInputScaleRadS;
  alglib::minqpcreate(variables_, a.state);
  alglib::minqpsetscale(a.state, a.scale);
  switch (params.algorithm) {
    case MpcQpAlgorithm::kDenseIpm:
      alglib::minqpsetalgodenseipm(a.state, params.solver_tolerance);
      break;
    case MpcQpAlgorithm::kBleic:
      alglib::minqpsetalgobleic(a.state, 0.0, 0.0, params.solver_tolerance, params.max_iterations);
      break;
    case MpcQpAlgorithm::kDenseAul:
      alglib::minqpsetalgodenseaul(a.state, params.solver_tolerance, 1000.0, 10);
      break;
  }
  // The rate rows never change: +1 on v_b,i, -1 on v_(b-1),i.
  int row = 0;
  for (int b = 1; b < blocks_; ++b) {
    for (int i = 0; i < nu_; ++i, ++row) {
      constraints_(row, InputIndex(b, i)) = 1.0;
      constraints_(row, InputIndex(b - 1, i)) = -1.0;
    }
  }
}

MpcQp::~MpcQp() = default;

void MpcQp::Condense(const MpcQpData& data) {
  const MultiArmMpcStateMatrix& A = data.step.a;
  MultiArmMpcState previous = data.initial;
  for (int k = 0; k < n_; ++k) {
    const int r = ns_ * k;
    previous = A * previous + data.step.c;
    offset_.segment(r, ns_) = previous;
    if (k > 0) gamma_.block(r, 0, ns_, nu_ * k).noalias() = A * gamma_.block(r - ns_, 0, ns_, nu_ * k);
    gamma_.block(r, nu_ * k, ns_, nu_) = data.step.b;
  }
  // Gamma E: the columns of a block's steps summed.
  for (int b = 0; b < blocks_; ++b) {
    auto columns = gamma_blocked_.middleCols(nu_ * b, nu_);
    columns.setZero();
    for (int k = block_start(b); k < block_start(b + 1); ++k) columns += gamma_.middleCols(nu_ * k, nu_);
  }
}

void MpcQp::BuildCost(const MpcQpData& data) {
  const int nv = nu_ * blocks_;
  // W = Qbar Gamma E, block row by block row; H = (Gamma E)^T W; g = W^T (o - r).
  for (int k = 0; k < n_; ++k) {
    const int r = ns_ * k;
    const int w = static_cast<int>(data.weights);
    const MultiArmMpcStateMatrix& Q = (k == n_ - 1) ? terminal_weight_[w] : stage_weight_[w];
    weighted_.middleRows(r, ns_).noalias() = Q * gamma_blocked_.middleRows(r, ns_);
    error_.segment(r, ns_) = offset_.segment(r, ns_) - data.reference.col(k);
  }
  hessian_.setZero();
  gradient_.setZero();
  hessian_.topLeftCorner(nv, nv).noalias() = 2.0 * gamma_blocked_.transpose() * weighted_;
  gradient_.head(nv).noalias() = 2.0 * weighted_.transpose() * error_;
  const double ru = params_.input_weight_s2_rad2, rd = params_.input_rate_weight_s2_rad2;
  for (int b = 0; b < blocks_; ++b) {
    const double length = block_start(b + 1) - block_start(b);
    for (int i = 0; i < nu_; ++i) {
      const int j = InputIndex(b, i);
      // The block's mean u_ff,i as its first value plus the mean deviation
      // from it: exactly the value when it is constant over the block.
      const double first = data.feed_forward_rad_s(i, block_start(b));
      double deviation_sum = 0.0;
      for (int k = block_start(b); k < block_start(b + 1); ++k) deviation_sum += data.feed_forward_rad_s(i, k) - first;
      const double feed_forward_mean = first + deviation_sum / length;
      hessian_(j, j) += 2.0 * (length * ru + rd);
      gradient_(j) -= 2.0 * length * ru * feed_forward_mean;
      if (b == 0) {
        gradient_(j) -= 2.0 * rd * data.last_command_rad_s(i);
      } else {
        const int p = InputIndex(b - 1, i);
        hessian_(p, p) += 2.0 * rd;
        hessian_(j, p) -= 2.0 * rd;
        hessian_(p, j) -= 2.0 * rd;
      }
    }
  }
  hessian_(nv, nv) = 2.0 * params_.tilt_slack_weight;
}

void MpcQp::BuildConstraints(const MpcQpData& data) {
  const double inf = std::numeric_limits<double>::infinity();
  const double step_change = params_.max_omega_rate_rad_s2 * params_.step_s;
  const double first_change = params_.max_omega_rate_rad_s2 * data.command_period_s;
  const int nv = nu_ * blocks_;
  int row = 0;
  for (int b = 1; b < blocks_; ++b) {
    for (int i = 0; i < nu_; ++i, ++row) {
      lower_(row) = -step_change;
      upper_(row) = step_change;
    }
  }
  const int slack = variables_ - 1;
  for (const int k : tilt_steps_) {
    const int r = ns_ * k + kMpcPhi;
    const double phi_free = offset_(r);
    // phi_k + eps >= -phi_max and phi_k - eps <= phi_max, phi_k = (Gamma E)_phi V + o_phi.
    constraints_.row(row).head(nv) = gamma_blocked_.row(r);
    constraints_(row, slack) = 1.0;
    lower_(row) = -params_.max_tilt_rad - phi_free;
    upper_(row) = inf;
    ++row;
    constraints_.row(row).head(nv) = gamma_blocked_.row(r);
    constraints_(row, slack) = -1.0;
    lower_(row) = -inf;
    upper_(row) = params_.max_tilt_rad - phi_free;
    ++row;
  }
  box_lower_.setZero();
  box_upper_.setConstant(omega_max_rad_s_);
  for (int i = 0; i < nu_; ++i) {
    const double last = std::clamp(data.last_command_rad_s(i), 0.0, omega_max_rad_s_);
    box_lower_(i) = std::max(0.0, last - first_change);
    box_upper_(i) = std::min(omega_max_rad_s_, last + first_change);
  }
  box_upper_(slack) = inf;
}

MpcSolveStatus MpcQp::Check(const Eigen::VectorXd& x) const {
  if (!x.allFinite()) return MpcSolveStatus::kNonFinite;
  for (int j = 0; j < variables_; ++j) {
    if (x(j) < box_lower_(j) - kMpcBoundToleranceRadS || x(j) > box_upper_(j) + kMpcBoundToleranceRadS)
      return MpcSolveStatus::kInfeasible;
  }
  const double step_change = params_.max_omega_rate_rad_s2 * params_.step_s;
  for (int b = 1; b < blocks_; ++b) {
    for (int i = 0; i < nu_; ++i) {
      if (std::fabs(x(InputIndex(b, i)) - x(InputIndex(b - 1, i))) > step_change + kMpcBoundToleranceRadS)
        return MpcSolveStatus::kInfeasible;
    }
  }
  return MpcSolveStatus::kSolved;
}

void MpcQp::WarmStart(const MpcQpData& data) {
  // The previous plan one step on (block b starts with what the old plan flew
  // one step after its start), or the feed-forward; clamped into the box.
  for (int b = 0; b < blocks_; ++b) {
    const int step = std::min(block_start(b) + 1, n_ - 1);
    int old_block = 0;
    while (old_block + 1 < blocks_ && block_start(old_block + 1) <= step) ++old_block;
    for (int i = 0; i < nu_; ++i)
      start_(InputIndex(b, i)) =
          has_solution_ ? solution_(InputIndex(old_block, i)) : data.feed_forward_rad_s(i, block_start(b));
  }
  start_(variables_ - 1) = 0.0;
  start_ = start_.cwiseMax(box_lower_).cwiseMin(box_upper_);
}

// Copies the problem into alglib's arrays and solves; false on an alglib error.
bool MpcQp::RunAlglib() {
  Alglib& a = *alglib_;
  try {
    const int rows = static_cast<int>(constraints_.rows());
    for (int r = 0; r < variables_; ++r) {
      for (int c = r; c < variables_; ++c) a.quadratic[r][c] = hessian_(r, c);
      a.linear[r] = gradient_(r);
      a.box_lower[r] = box_lower_(r);
      a.box_upper[r] = std::isfinite(box_upper_(r)) ? box_upper_(r) : alglib::fp_posinf;
      a.start[r] = start_(r);
    }
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < variables_; ++c) a.constraints[r][c] = constraints_(r, c);
      a.lower[r] = std::isfinite(lower_(r)) ? lower_(r) : alglib::fp_neginf;
      a.upper[r] = std::isfinite(upper_(r)) ? upper_(r) : alglib::fp_posinf;
    }
    alglib::minqpsetquadraticterm(a.state, a.quadratic, true);
    alglib::minqpsetlinearterm(a.state, a.linear);
    alglib::minqpsetbc(a.state, a.box_lower, a.box_upper);
    alglib::minqpsetlc2dense(a.state, a.constraints, a.lower, a.upper, rows);
    alglib::minqpsetstartingpoint(a.state, a.start);
    alglib::minqpoptimize(a.state);
    alglib::minqpresultsbuf(a.state, a.x, a.report);
  } catch (const alglib::ap_error&) {
    return false;
  }
  return true;
}

MpcQpSolution MpcQp::Solve(const MpcQpData& data) {
  Condense(data);
  BuildCost(data);
  BuildConstraints(data);
  WarmStart(data);
  MpcQpSolution out;
  out.first_command_rad_s = MultiArmMpcInputs::Zero(nu_);
  if (!RunAlglib()) return out;
  const Alglib& a = *alglib_;
  out.termination_type = static_cast<int>(a.report.terminationtype);
  // DENSE-AUL leaves the iteration counts at 0: its factorizations stand in.
  out.iterations = static_cast<int>(a.report.inneriterationscount + a.report.outeriterationscount);
  if (out.iterations == 0) out.iterations = static_cast<int>(a.report.ncholesky);
  if (out.iterations == 0) out.iterations = static_cast<int>(a.report.nmv);
  if (out.termination_type <= 0) return out;
  for (int j = 0; j < variables_; ++j) last_x_(j) = a.x[j];
  out.status = Check(last_x_);
  if (out.status != MpcSolveStatus::kSolved) return out;
  last_x_ = last_x_.cwiseMax(box_lower_).cwiseMin(box_upper_);
  solution_ = last_x_;
  has_solution_ = true;
  out.first_command_rad_s = solution_.head(nu_);
  out.tilt_slack_rad = solution_(variables_ - 1);
  return out;
}

MultiArmMpcState MpcQp::PredictedState(int k) const {
  const int r = ns_ * (k - 1);
  return gamma_blocked_.middleRows(r, ns_) * last_x_.head(nu_ * blocks_) + offset_.segment(r, ns_);
}

}  // namespace birotor
