#include "controller/multi_arm_mpc.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>

#include "model/plant.h"

namespace birotor {
namespace {

// This thread's CPU time [s].
double ThreadCpuS() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

MpcOutcome OutcomeOf(MpcSolveStatus status) {
  switch (status) {
    case MpcSolveStatus::kSolved:
      return MpcOutcome::kSolved;
    case MpcSolveStatus::kNonFinite:
      return MpcOutcome::kNonFinite;
    case MpcSolveStatus::kInfeasible:
      return MpcOutcome::kInfeasible;
    case MpcSolveStatus::kSolverFailed:
      break;
  }
  return MpcOutcome::kSolverFailed;
}

}  // namespace

MultiArmMpcStateMatrix MultiArmMpc::TerminalWeight(const MultiArmMpcModel& model, const MpcParams& params) {
  return MpcQp::TerminalWeight(
      model.Linearize(model.HoverState(), model.hover_speed_rad_s(), model.NominalContext(), params.step_s), params);
}

MpcParams MultiArmMpc::PlanningParams(const MpcParams& params, bool fully_actuated) {
  MpcParams out = params;
  if (fully_actuated) {
    out.tilt_weight_1_rad2 = params.level_tilt_weight_1_rad2;
    out.pitch_rate_weight_s2_rad2 = params.level_pitch_rate_weight_s2_rad2;
  }
  return out;
}

MultiArmMpc::MultiArmMpc(const VehicleDescription& vehicle, const MpcParams& params)
    : vehicle_(vehicle),
      fully_actuated_(MultiArmControlModeFor(vehicle) == MultiArmControlMode::kFullyActuated),
      params_(PlanningParams(params, fully_actuated_)),
      model_(vehicle),
      qp_(params_, vehicle.arm_count, vehicle.omega_max_rad_s, TerminalWeight(model_, params_)),
      allocator_(vehicle, MultiArmControlModeFor(vehicle)),
      omega_estimate_rad_s_(model_.hover_speed_rad_s()) {
  const int nu = vehicle.arm_count, ns = model_.state_size();
  data_.initial = MultiArmMpcState::Zero(ns);
  data_.reference = Eigen::MatrixXd::Zero(ns, params_.horizon_steps);
  data_.feed_forward_rad_s = Eigen::MatrixXd::Zero(nu, params_.horizon_steps);
  data_.last_command_rad_s = MultiArmMpcInputs::Zero(nu);
  qp_.SetTerminalWeight(MpcWeightSet::kTiltedHover,
                        TerminalWeight(model_, MpcQp::WeightParams(params_, MpcWeightSet::kTiltedHover)));
}

double MultiArmMpc::ReferenceTilt(const Eigen::Vector2d& acceleration_m_s2, const MultiArmHoverBase* base) const {
  if (fully_actuated_) return base != nullptr ? base->tilt_rad : 0.0;
  const double g = vehicle_.gravity_m_s2;
  return std::clamp(std::atan2(-acceleration_m_s2.x(), std::max(g + acceleration_m_s2.y(), 0.1 * g)),
                    -params_.max_tilt_rad, params_.max_tilt_rad);
}

MultiArmMpcInputs MultiArmMpc::FeedForward(const Eigen::Vector2d& acceleration_m_s2,
                                           const MultiArmMpcInputs& efficiency, const MultiArmHoverBase* base) const {
  const int nu = rotors();
  MultiArmMpcInputs omega(nu);
  if (fully_actuated_) {
    const double m = vehicle_.TotalMass();
    RotorEfficiencies e = NominalEfficiencies();
    for (int i = 0; i < nu; ++i) e[static_cast<size_t>(i)] = efficiency(i);
    Eigen::Vector3d change(m * acceleration_m_s2.x(), m * acceleration_m_s2.y(), 0.0);  // level: body = world
    if (base != nullptr && base->tilt_rad != 0.0) {
      // [F_x; F_z] = R(phi_b)^T m (a + g e_z), less what the base makes, m g [sin phi_b, cos phi_b].
      const double c = std::cos(base->tilt_rad), s = std::sin(base->tilt_rad), g = vehicle_.gravity_m_s2;
      const Eigen::Vector2d world_n = m * Eigen::Vector2d(acceleration_m_s2.x(), acceleration_m_s2.y() + g);
      change.x() = c * world_n.x() + s * world_n.y() - m * g * s;
      change.y() = -s * world_n.x() + c * world_n.y() - m * g * c;
    }
    const MultiArmRotorCommand command =
        allocator_.Allocate(base != nullptr ? base->force_n : ArmForces<double>(model_.hover_force_n()), change, e);
    for (int i = 0; i < nu; ++i) omega(i) = command.omega_cmd_rad_s[static_cast<size_t>(i)];
    return omega;
  }
  const double g = vehicle_.gravity_m_s2;
  const double scale = std::hypot(acceleration_m_s2.x(), std::max(g + acceleration_m_s2.y(), 0.1 * g)) / g;
  for (int i = 0; i < nu; ++i) {
    omega(i) = RotorSpeedForThrust(vehicle_.arms[static_cast<size_t>(i)].thrust_coeff_n_s2_rad2,
                                   vehicle_.omega_max_rad_s, scale * model_.hover_force_n()(i), efficiency(i));
  }
  return omega;
}

void MultiArmMpc::ExtrapolateReference(const ReferencePoint& now, double step_s, std::vector<ReferencePoint>* horizon) {
  for (size_t k = 0; k < horizon->size(); ++k) {
    const double t = step_s * static_cast<double>(k + 1);
    ReferencePoint& r = (*horizon)[k];
    r.position_m = now.position_m + t * now.velocity_m_s + 0.5 * t * t * now.acceleration_m_s2;
    r.velocity_m_s = now.velocity_m_s + t * now.acceleration_m_s2;
    r.acceleration_m_s2 = now.acceleration_m_s2;
  }
}

void MultiArmMpc::Advance(const MultiArmMpcInputs& omega_cmd_rad_s, double dt_s) {
  for (int i = 0; i < rotors(); ++i) {
    const double tau_m = vehicle_.arms[static_cast<size_t>(i)].motor_time_constant_s;
    omega_estimate_rad_s_(i) =
        MotorStep(omega_estimate_rad_s_(i), ClampCommand(vehicle_.omega_max_rad_s, omega_cmd_rad_s(i)), tau_m, dt_s);
  }
}

MultiArmMpcInputs MultiArmMpc::Fallback(const MultiArmMpcInputs& efficiency,
                                        const MultiArmMpcInputs& last_command_rad_s) const {
  MultiArmMpcInputs out(rotors());
  for (int i = 0; i < rotors(); ++i) {
    const double hover =
        RotorSpeedForThrust(vehicle_.arms[static_cast<size_t>(i)].thrust_coeff_n_s2_rad2, vehicle_.omega_max_rad_s,
                            model_.hover_force_n()(i), std::isfinite(efficiency(i)) ? efficiency(i) : 1.0);
    const double last = last_command_rad_s(i);
    out(i) = std::isfinite(last) ? ClampCommand(vehicle_.omega_max_rad_s, last) : hover;
  }
  return out;
}

void MultiArmMpc::FillData(const BodyState& measured, const std::vector<ReferencePoint>& reference,
                           const MultiArmMpcInputs& efficiency, const MultiArmMpcInputs& last_command_rad_s,
                           double period_s, const MultiArmHoverBase* base) {
  const int nu = rotors();
  MultiArmMpcState& s0 = data_.initial;
  s0.segment<2>(kMpcX) = measured.position_m;
  s0(kMpcPhi) = measured.phi_rad;
  s0.segment<2>(kMpcXDot) = measured.velocity_m_s;
  s0(kMpcPhiDot) = measured.phi_dot_rad_s;
  s0.tail(nu) = omega_estimate_rad_s_;
  MultiArmMpcContext context;
  context.efficiency = efficiency;
  data_.step = model_.Linearize(s0, last_command_rad_s, context, params_.step_s);
  data_.last_command_rad_s = last_command_rad_s;
  data_.command_period_s = period_s;
  // About a tilted hover: tilting to move (MpcParams tilted_hover_*).
  const bool tilted = fully_actuated_ && base != nullptr && base->tilt_rad != 0.0;
  data_.weights = tilted ? MpcWeightSet::kTiltedHover : MpcWeightSet::kTracking;
  const size_t samples = reference.size();
  for (int k = 0; k < params_.horizon_steps; ++k) {
    const ReferencePoint& r = reference[std::min(static_cast<size_t>(k), samples - 1)];
    const MultiArmMpcInputs feed_forward = FeedForward(r.acceleration_m_s2, efficiency, base);
    auto column = data_.reference.col(k);
    column(kMpcX) = r.position_m.x();
    column(kMpcZ) = r.position_m.y();
    column(kMpcPhi) = ReferenceTilt(r.acceleration_m_s2, base);
    column(kMpcXDot) = r.velocity_m_s.x();
    column(kMpcZDot) = r.velocity_m_s.y();
    column(kMpcPhiDot) = 0.0;
    column.tail(nu) = feed_forward;
    data_.feed_forward_rad_s.col(k) = feed_forward;
  }
}

MultiArmMpcResult MultiArmMpc::Solve(const BodyState& measured, const std::vector<ReferencePoint>& reference,
                                     const MultiArmMpcInputs& efficiency, const MultiArmMpcInputs& last_command_rad_s,
                                     double period_s, const MultiArmHoverBase* base) {
  const auto start = std::chrono::steady_clock::now();
  const double start_cpu_s = ThreadCpuS();
  MultiArmMpcResult out;
  out.omega_cmd_rad_s = Fallback(efficiency, last_command_rad_s);
  const bool inputs_ok = !reference.empty() && efficiency.size() == rotors() && efficiency.allFinite() &&
                         (efficiency.array() > 0.0).all() && last_command_rad_s.size() == rotors() &&
                         last_command_rad_s.allFinite();
  if (inputs_ok) {
    FillData(measured, reference, efficiency, last_command_rad_s, period_s, base);
    const MpcQpSolution solution = qp_.Solve(data_);
    out.outcome = OutcomeOf(solution.status);
    out.iterations = solution.iterations;
    out.tilt_slack_rad = solution.tilt_slack_rad;
    if (out.outcome == MpcOutcome::kSolved) out.omega_cmd_rad_s = solution.first_command_rad_s;
  }
  out.solve_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.solve_cpu_s = ThreadCpuS() - start_cpu_s;
  const bool late = params_.deadline_clock == MpcDeadlineClock::kWork   ? out.iterations > params_.deadline_work
                    : params_.deadline_clock == MpcDeadlineClock::kWall ? out.solve_time_s > params_.deadline_s
                                                                        : out.solve_cpu_s > params_.deadline_s;
  if (out.outcome == MpcOutcome::kSolved && late) {
    out.outcome = MpcOutcome::kLate;
    out.omega_cmd_rad_s = Fallback(efficiency, last_command_rad_s);
  }
  out.solved = out.outcome == MpcOutcome::kSolved;
  return out;
}

}  // namespace birotor
