#include "controller/multi_arm_mpc_flight.h"

#include <algorithm>
#include <cmath>

#include "controller/multi_arm_mpc.h"
#include "model/multi_arm_linearization.h"
#include "model/multi_arm_plant.h"

namespace birotor {
namespace {

BodyState BodyOf(const VehicleDescription& vehicle, const MultiArmPlantState& x) {
  BodyState body;
  body.position_m = Eigen::Vector2d(x(MultiArmQIndex(vehicle, kX)), x(MultiArmQIndex(vehicle, kZ)));
  body.phi_rad = x(MultiArmQIndex(vehicle, kPhi));
  body.velocity_m_s = Eigen::Vector2d(x(MultiArmVIndex(vehicle, kX)), x(MultiArmVIndex(vehicle, kZ)));
  body.phi_dot_rad_s = x(MultiArmVIndex(vehicle, kPhi));
  return body;
}

}  // namespace

MultiArmMpcFlightResult FlyMultiArmMpc(const VehicleDescription& vehicle, const MpcParams& params,
                                       const MultiArmMpcFlightOptions& options) {
  MultiArmMpc mpc(vehicle, params);
  const int nu = vehicle.arm_count;
  MultiArmPlantState x = MultiArmHoverPlantState(vehicle, SolveMultiArmHover(vehicle));
  const double period_s = 1.0 / params.rate_hz;
  const int plant_steps_per_period = std::max(1, static_cast<int>(std::lround(period_s / options.plant_step_s)));
  const double plant_dt_s = period_s / plant_steps_per_period;
  const int periods = static_cast<int>(std::lround(options.duration_s / period_s));

  ReferencePoint target;
  target.position_m = options.target_m;
  std::vector<ReferencePoint> reference(static_cast<size_t>(params.horizon_steps));
  MultiArmMpc::ExtrapolateReference(target, params.step_s, &reference);
  MultiArmMpcInputs efficiency(nu);
  for (int i = 0; i < nu; ++i) efficiency(i) = options.planned_efficiency[static_cast<size_t>(i)];
  MultiArmMpcInputs command = mpc.rotor_speed_estimate_rad_s();
  MultiArmPlantInput input;
  input.thrust_scale = options.plant_efficiency;

  MultiArmMpcFlightResult out;
  out.solve_cpu_s.reserve(static_cast<size_t>(periods));
  out.solve_wall_s.reserve(static_cast<size_t>(periods));
  out.settle_s = 0.0;
  for (int period = 0; period < periods; ++period) {
    const MultiArmMpcResult result = mpc.Solve(BodyOf(vehicle, x), reference, efficiency, command, period_s);
    ++out.solves;
    out.fallbacks += result.solved ? 0 : 1;
    out.solver_failed += result.outcome == MpcOutcome::kSolverFailed ? 1 : 0;
    out.non_finite += result.outcome == MpcOutcome::kNonFinite ? 1 : 0;
    out.infeasible += result.outcome == MpcOutcome::kInfeasible ? 1 : 0;
    out.late += result.outcome == MpcOutcome::kLate ? 1 : 0;
    out.max_iterations = std::max(out.max_iterations, result.iterations);
    out.solve_cpu_s.push_back(result.solve_cpu_s);
    out.solve_wall_s.push_back(result.solve_time_s);
    command = result.omega_cmd_rad_s;
    for (int i = 0; i < nu; ++i) input.omega_cmd_rad_s[static_cast<size_t>(i)] = command(i);
    for (int k = 0; k < plant_steps_per_period; ++k) {
      x = StepMultiArmPlant(vehicle, x, input, plant_dt_s);
      const BodyState body = BodyOf(vehicle, x);
      out.peak_tilt_rad = std::max(out.peak_tilt_rad, std::abs(body.phi_rad));
      out.peak_x_overshoot_m = std::max(out.peak_x_overshoot_m, body.position_m.x() - options.target_m.x());
      out.peak_altitude_error_m =
          std::max(out.peak_altitude_error_m, std::abs(body.position_m.y() - options.target_m.y()));
      if ((body.position_m - options.target_m).norm() > options.settle_band_m)
        out.settle_s = (period + static_cast<double>(k + 1) / plant_steps_per_period) * period_s;
    }
    mpc.Advance(command, period_s);
  }
  const BodyState end = BodyOf(vehicle, x);
  out.final_position_m = end.position_m;
  out.final_speed_m_s = end.velocity_m_s.norm();
  return out;
}

}  // namespace birotor
