#include "simulator/multi_arm_autopilot.h"

namespace birotor {

MultiArmAutopilot::MultiArmAutopilot(const VehicleDescription& vehicle, const ControllerParams& gains,
                                     const MultiArmHover& hover)
    : vehicle_(vehicle), law_(vehicle, gains, hover) {}

MultiArmRotorCommand MultiArmAutopilot::Update(const MultiArmPlantState& state, const ReferencePoint& reference) {
  const VehicleDescription& v = vehicle_;
  BodyState body;
  body.position_m = Eigen::Vector2d(state(MultiArmQIndex(v, kX)), state(MultiArmQIndex(v, kZ)));
  body.velocity_m_s = Eigen::Vector2d(state(MultiArmVIndex(v, kX)), state(MultiArmVIndex(v, kZ)));
  body.phi_rad = state(MultiArmQIndex(v, kPhi));
  body.phi_dot_rad_s = state(MultiArmVIndex(v, kPhi));
  // Nominal thrust map only: the autopilot does not know mu_i.
  return law_.Update(body, reference, NominalEfficiencies());
}

}  // namespace birotor
