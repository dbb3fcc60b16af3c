#include "simulator/ground_phase.h"

namespace birotor {

GroundPhase::GroundPhase(const Scenario& scenario) : params_(scenario.ground) {
  if (!params_.enabled) return;
  on_ground_ = true;
  support_z_m_ = scenario.start_position_m[1];
  if (params_.land) {
    disarm_s_ = scenario.duration_s - params_.rest_after_s;
    land_start_s_ = disarm_s_ - params_.landing_duration_s;
  }
}

bool GroundPhase::PhaseCommand(double t_s, double* omega_cmd_rad_s) const {
  if (!params_.enabled) return false;
  if (t_s < params_.rest_s || (params_.land && t_s >= disarm_s_)) {
    *omega_cmd_rad_s = 0.0;  // stopped
    return true;
  }
  if (t_s < params_.FlightStartS()) {
    const double ramp = params_.spool_up_s > 0 ? (t_s - params_.rest_s) / params_.spool_up_s : 1.0;
    *omega_cmd_rad_s = params_.idle_rad_s * ramp;
    return true;
  }
  return false;
}

ReferencePoint GroundPhase::FlightReference(double t_s, const Trajectory& trajectory) {
  const double flight_s = t_s - params_.FlightStartS();
  if (!(params_.enabled && params_.land && t_s >= land_start_s_)) return trajectory.At(flight_s);
  if (!landing_planned_) {
    // Vertical descent from where the reference is to the support height.
    const ReferencePoint from = trajectory.At(flight_s);
    landing_.start_s = land_start_s_;
    landing_.duration_s = params_.landing_duration_s;
    landing_.from_m = from.position_m;
    landing_.to_m = Eigen::Vector2d(from.position_m.x(), support_z_m_);
    landing_planned_ = true;
  }
  return EvaluateQuintic(landing_, t_s);
}

bool GroundPhase::Touchdown(double z_m) {
  if (!params_.enabled || on_ground_ || z_m > support_z_m_) return false;
  on_ground_ = true;
  return true;
}

}  // namespace birotor
