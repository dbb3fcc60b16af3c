#include "simulator/flight_controller.h"

#include "samples/rotor_count.h"

namespace birotor {

FlightController::FlightController(const BirotorParams& vehicle, const ControllerParams& params, double hover_force_n)
    : vehicle_(vehicle), law_(vehicle, params, hover_force_n) {}

RotorCommand FlightController::Update(const PlantState& state, const ReferencePoint& reference) {
  BodyState body;
  body.position_m = Eigen::Vector2d(state(kPlantQ + kX), state(kPlantQ + kZ));
  body.velocity_m_s = Eigen::Vector2d(state(kPlantV + kX), state(kPlantV + kZ));
  body.phi_rad = state(kPlantQ + kPhi);
  body.phi_dot_rad_s = state(kPlantV + kPhi);
  const RotorForces forces = law_.Update(body, reference);
  RotorCommand command;
  // Nominal thrust map only: the autopilot does not know mu_i.
  for (int i = 0; i < kBirotorRotors; ++i)
    command.omega_cmd_rad_s[i] = RotorSpeedForThrust(vehicle_, forces.force_n[i], 1.0);
  return command;
}

}  // namespace birotor
