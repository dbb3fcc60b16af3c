#include "controller/mpc_controller.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>

#include "model/plant.h"
#include "numerics/percentile.h"

namespace birotor {
namespace {

// Hover state of the prediction model: level, at rest, rotors at hover speed.
MpcState HoverState(double omega_rad_s) {
  MpcState s = MpcState::Zero();
  s(kMpcOmega1) = s(kMpcOmega2) = omega_rad_s;
  return s;
}

// This thread's CPU time [s].
double ThreadCpuS() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

MultiArmMpcStateMatrix MpcController::TerminalWeight(const MpcPredictionModel& model, const MpcParams& params) {
  const double omega_hover = RotorSpeedForThrust(model.vehicle(), model.hover_force_n(), 1.0);
  const MpcLinearStep step = model.Linearize(HoverState(omega_hover), Eigen::Vector2d::Constant(omega_hover),
                                             MpcModelContext(), params.step_s);
  const MpcStateMatrix stage_weight = MpcQp::StageWeight(params, kMpcInputSize);
  return MpcRiccatiTerminalWeight(step.a, step.b, stage_weight, params.input_weight_s2_rad2);
}

MpcController::MpcController(const BirotorParams& vehicle, const MpcParams& params)
    : vehicle_(vehicle),
      params_(params),
      model_(vehicle),
      qp_(params, kMpcInputSize, vehicle.omega_max_rad_s, TerminalWeight(model_, params)) {
  data_.initial = MultiArmMpcState::Zero(kMpcStateSize);
  data_.reference = Eigen::MatrixXd::Zero(kMpcStateSize, params.horizon_steps);
  data_.feed_forward_rad_s = Eigen::MatrixXd::Zero(kMpcInputSize, params.horizon_steps);
  data_.last_command_rad_s = MultiArmMpcInputs::Zero(kMpcInputSize);
  for (const MpcWeightSet set : {MpcWeightSet::kRecovery, MpcWeightSet::kDescent, MpcWeightSet::kSteady})
    qp_.SetTerminalWeight(set, TerminalWeight(model_, MpcQp::WeightParams(params, set)));
  omega_estimate_rad_s_.setConstant(RotorSpeedForThrust(vehicle, model_.hover_force_n(), 1.0));
}

void MpcController::Advance(const Eigen::Vector2d& omega_cmd_rad_s, double dt_s) {
  for (int i = 0; i < kMpcInputSize; ++i) {
    omega_estimate_rad_s_(i) = MotorStep(omega_estimate_rad_s_(i), ClampCommand(vehicle_, omega_cmd_rad_s(i)),
                                         vehicle_.motor_time_constant_s, dt_s);
  }
  sent_since_previous_ = omega_cmd_rad_s.cwiseMax(0.0).cwiseMin(vehicle_.omega_max_rad_s);
  elapsed_since_previous_s_ += dt_s;
  ++advances_since_previous_;
}

// d <- d + alpha (d_seen - d): d_seen is the velocity the model missed over
// the last period divided by its length, plus the disturbance it already had.
void MpcController::UpdateDisturbance(const MpcState& now) {
  const double dt = elapsed_since_previous_s_;
  recovery_left_s_ = std::max(0.0, recovery_left_s_ - dt);
  if (!has_previous_ || advances_since_previous_ != 1 || dt <= 0.0) return;
  const MpcState predicted = model_.Step(previous_state_, sent_since_previous_, previous_context_, dt);
  const Eigen::Vector3d seen =
      (now.segment<3>(kMpcXDot) - predicted.segment<3>(kMpcXDot)) / dt + previous_context_.disturbance;
  const double alpha = dt / (params_.disturbance_time_constant_s + dt);
  if (!seen.allFinite()) return;
  disturbance_ += alpha * (seen - disturbance_);
  const double pitch_step = params_.disturbance_pitch_step_rad_s2;
  if (pitch_step > 0.0 && std::abs(seen(2) - disturbance_(2)) > pitch_step) {
    disturbance_(2) = seen(2);
    recovery_left_s_ = params_.recovery_s;
    ++stats_.recoveries;
  }
  const double a = params_.max_disturbance_m_s2, w = params_.max_disturbance_rad_s2;
  disturbance_(0) = std::clamp(disturbance_(0), -a, a);
  disturbance_(1) = std::clamp(disturbance_(1), -a, a);
  disturbance_(2) = std::clamp(disturbance_(2), -w, w);
}

// The disturbance is what the model does not explain: when the model's
// efficiencies change, the acceleration they now explain at this state
// leaves it (d -= a(s, u, new) - a(s, u, old), at most down to 0), so a loss first taken as a
// disturbance is not counted twice once FORCE reports it.
void MpcController::RebaseDisturbance(const MpcState& now, const Eigen::Vector2d& command_rad_s,
                                      const MpcModelContext& context) {
  if (!has_previous_ || context.thrust_scale == previous_context_.thrust_scale) return;
  MpcModelContext before = context;
  before.thrust_scale = previous_context_.thrust_scale;
  const MpcState explained =
      model_.Derivative(now, command_rad_s, context) - model_.Derivative(now, command_rad_s, before);
  for (int j = 0; j < 3; ++j) {
    const double held = disturbance_(j), change = explained(kMpcXDot + j);
    // Never more than it holds: d moves towards 0, not past it.
    if (held * change > 0.0) disturbance_(j) = held - std::copysign(std::min(std::abs(change), std::abs(held)), held);
  }
}

void MpcController::FillReference(const MpcPlanInput& input, const Eigen::Vector2d& feed_forward_rad_s) {
  const ReferencePoint& r = input.reference;
  const double g = vehicle_.gravity_m_s2;
  const double tilt = std::clamp(std::atan2(-r.acceleration_m_s2.x(), std::max(g + r.acceleration_m_s2.y(), 0.1 * g)),
                                 -params_.max_tilt_rad, params_.max_tilt_rad);
  for (int k = 0; k < params_.horizon_steps; ++k) {
    const double t = params_.step_s * (k + 1);
    auto column = data_.reference.col(k);
    const Eigen::Vector2d p = r.position_m + t * r.velocity_m_s + 0.5 * t * t * r.acceleration_m_s2;
    const Eigen::Vector2d v = r.velocity_m_s + t * r.acceleration_m_s2;
    column(kMpcX) = p.x();
    column(kMpcZ) = p.y();
    column(kMpcPhi) = tilt;
    column(kMpcXDot) = v.x();
    column(kMpcZDot) = v.y();
    column(kMpcPhiDot) = 0.0;
    column(kMpcOmega1) = feed_forward_rad_s(0);
    column(kMpcOmega2) = feed_forward_rad_s(1);
  }
}

MpcPlan MpcController::Plan(const MpcPlanInput& input) {
  const auto start = std::chrono::steady_clock::now();
  const double start_cpu_s = ThreadCpuS();
  MpcState s0;
  s0 << input.state.position_m, input.state.phi_rad, input.state.velocity_m_s, input.state.phi_dot_rad_s,
      omega_estimate_rad_s_;
  UpdateDisturbance(s0);

  MpcModelContext context;
  context.thrust_scale = params_.use_thrust_scale ? input.thrust_scale : Eigen::Vector2d::Ones();
  RebaseDisturbance(s0, input.last_command_rad_s, context);
  context.disturbance = disturbance_;
  // Feed-forward: the thrust that makes the reference acceleration, half per rotor.
  const Eigen::Vector2d a = input.reference.acceleration_m_s2;
  const double g = vehicle_.gravity_m_s2;
  const double total_n = 2.0 * model_.hover_force_n() * std::hypot(a.x(), std::max(g + a.y(), 0.1 * g)) / g;
  Eigen::Vector2d feed_forward;
  for (int i = 0; i < kMpcInputSize; ++i)
    feed_forward(i) = RotorSpeedForThrust(vehicle_, 0.5 * total_n, context.thrust_scale(i));

  data_.initial = s0;
  data_.step = Generalized(model_.Linearize(s0, input.last_command_rad_s, context, params_.step_s));
  data_.feed_forward_rad_s.colwise() = feed_forward;  // held over the horizon
  data_.last_command_rad_s = input.last_command_rad_s;
  data_.command_period_s = input.period_s;
  // A steady reference (a hover, a slow move): the pitch damped harder.
  const bool steady = input.reference.acceleration_m_s2.norm() < params_.steady_max_accel_m_s2;
  data_.weights = input.level_descent      ? MpcWeightSet::kDescent
                  : recovery_left_s_ > 0.0 ? MpcWeightSet::kRecovery
                  : steady                 ? MpcWeightSet::kSteady
                                           : MpcWeightSet::kTracking;
  FillReference(input, feed_forward);
  const MpcQpSolution solution = qp_.Solve(data_);

  MpcPlan plan;
  plan.iterations = solution.iterations;
  plan.tilt_slack_rad = solution.tilt_slack_rad;
  plan.omega_cmd_rad_s = solution.first_command_rad_s.head<kMpcInputSize>();
  switch (solution.status) {
    case MpcSolveStatus::kSolved:
      plan.outcome = MpcOutcome::kSolved;
      break;
    case MpcSolveStatus::kSolverFailed:
      plan.outcome = MpcOutcome::kSolverFailed;
      break;
    case MpcSolveStatus::kNonFinite:
      plan.outcome = MpcOutcome::kNonFinite;
      break;
    case MpcSolveStatus::kInfeasible:
      plan.outcome = MpcOutcome::kInfeasible;
      break;
  }
  plan.solve_time_s = params_.deadline_clock == MpcDeadlineClock::kWall
                          ? std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
                          : ThreadCpuS() - start_cpu_s;
  const bool late = params_.deadline_clock == MpcDeadlineClock::kWork ? plan.iterations > params_.deadline_work
                                                                      : plan.solve_time_s > params_.deadline_s;
  if (plan.outcome == MpcOutcome::kSolved && late) plan.outcome = MpcOutcome::kLate;

  has_previous_ = true;
  previous_state_ = s0;
  previous_context_ = context;
  elapsed_since_previous_s_ = 0.0;
  advances_since_previous_ = 0;
  Record(plan);
  return plan;
}

MpcPeriod MpcController::Fly(MpcPlanInput input, const Eigen::Vector2d& cascade_rad_s, bool attempt) {
  MpcPeriod out;
  const bool first = !flown_;
  if (first) input.last_command_rad_s = omega_estimate_rad_s_;
  out.omega_cmd_rad_s = cascade_rad_s;
  if (attempt) {
    out.planned = true;
    out.plan = Plan(input);
    out.fell_back = out.plan.outcome != MpcOutcome::kSolved;
    if (!out.fell_back) out.omega_cmd_rad_s = out.plan.omega_cmd_rad_s;
  }
  const double change = params_.max_omega_rate_rad_s2 * input.period_s;
  for (int i = 0; i < kMpcInputSize; ++i) {
    double omega = std::isfinite(out.omega_cmd_rad_s(i)) ? out.omega_cmd_rad_s(i) : input.last_command_rad_s(i);
    if (!first) omega = std::clamp(omega, input.last_command_rad_s(i) - change, input.last_command_rad_s(i) + change);
    out.omega_cmd_rad_s(i) = std::clamp(omega, 0.0, vehicle_.omega_max_rad_s);
  }
  flown_ = true;
  return out;
}

void MpcController::Record(const MpcPlan& plan) {
  ++stats_.solves;
  switch (plan.outcome) {
    case MpcOutcome::kSolved:
      break;
    case MpcOutcome::kSolverFailed:
      ++stats_.solver_failed;
      break;
    case MpcOutcome::kNonFinite:
      ++stats_.non_finite;
      break;
    case MpcOutcome::kInfeasible:
      ++stats_.infeasible;
      break;
    case MpcOutcome::kLate:
      ++stats_.late;
      break;
  }
  stats_.last_iterations = plan.iterations;
  stats_.max_iterations = std::max(stats_.max_iterations, plan.iterations);
  solve_times_.Record(plan.solve_time_s);
}

MpcStats MpcController::Stats() const {
  MpcStats out = stats_;
  solve_times_.Fill(&out);
  return out;
}

void MpcSolveTimes::Record(double solve_time_s) {
  max_s_ = std::max(max_s_, solve_time_s);
  times_s_[static_cast<size_t>(recorded_ % kMpcTimeWindow)] = solve_time_s;
  ++recorded_;
}

void MpcSolveTimes::Fill(MpcStats* stats) const {
  const size_t n = static_cast<size_t>(std::min<int64_t>(recorded_, kMpcTimeWindow));
  if (n == 0) return;
  std::copy(times_s_.begin(), times_s_.begin() + static_cast<std::ptrdiff_t>(n), scratch_.begin());
  const auto end = scratch_.begin() + static_cast<std::ptrdiff_t>(n);
  stats->solve_p50_s = Percentile(scratch_.begin(), end, 0.5);
  stats->solve_p99_s = Percentile(scratch_.begin(), end, 0.99);
  stats->solve_max_s = max_s_;
}

}  // namespace birotor
