#include "simulator/trajectory.h"

#include <algorithm>

#include "simulator/noise.h"

namespace birotor {
namespace {
constexpr uint64_t kTrajectoryStream = 101;
}  // namespace

ReferencePoint EvaluateQuintic(const QuinticMove& move, double t_s) {
  const double tau = std::clamp((t_s - move.start_s) / move.duration_s, 0.0, 1.0);
  const double tau2 = tau * tau, tau3 = tau2 * tau;
  const double s = tau3 * (10.0 - 15.0 * tau + 6.0 * tau2);
  const double s_dot = 30.0 * tau2 * (1.0 - 2.0 * tau + tau2) / move.duration_s;
  const double s_ddot = 60.0 * tau * (1.0 - 3.0 * tau + 2.0 * tau2) / (move.duration_s * move.duration_s);
  const Eigen::Vector2d delta = move.to_m - move.from_m;
  ReferencePoint out;
  out.position_m = move.from_m + s * delta;
  out.velocity_m_s = s_dot * delta;
  out.acceleration_m_s2 = s_ddot * delta;
  return out;
}

Trajectory::Trajectory(const Scenario& scenario)
    : start_m_(scenario.start_position_m[0], scenario.start_position_m[1]) {
  const TrajectoryParams& params = scenario.trajectory;
  Eigen::Vector2d position = start_m_;
  if (params.kind == "waypoints") {
    for (const Waypoint& w : params.waypoints) {
      const Eigen::Vector2d target(w.x_m, w.z_m);
      moves_.push_back({w.start_s, w.duration_s, position, target});
      position = target;
    }
  } else if (params.kind == "random_steps") {
    const RandomSteps& steps = params.random_steps;
    GaussianSource source(scenario.seed, kTrajectoryStream);
    for (double t = steps.interval_s; t + steps.move_duration_s <= scenario.duration_s; t += steps.interval_s) {
      Eigen::Vector2d target = position;
      for (int axis = 0; axis < 2; ++axis) {
        const double step = steps.max_step_m * (2.0 * source.Uniform() - 1.0);
        target(axis) = std::clamp(position(axis) + step, start_m_(axis) - steps.max_excursion_m,
                                  start_m_(axis) + steps.max_excursion_m);
      }
      moves_.push_back({t, steps.move_duration_s, position, target});
      position = target;
    }
  }
}

ReferencePoint Trajectory::At(double t_s) const {
  // Last move that has started; moves are few (<100), a linear scan is cheap.
  const QuinticMove* active = nullptr;
  for (const QuinticMove& move : moves_) {
    if (move.start_s > t_s) break;
    active = &move;
  }
  if (active == nullptr) {
    ReferencePoint hold;
    hold.position_m = start_m_;
    return hold;
  }
  return EvaluateQuintic(*active, t_s);
}

}  // namespace birotor
