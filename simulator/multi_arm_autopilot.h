// The simulator's autopilot for any VehicleDescription: the cascade of
// controller/multi_arm_law.h (the gains and stages of
// controller/position_attitude_law.h, the allocation of
// controller/wrench_allocation.h) on the TRUE rigid-body state, with the
// NOMINAL map omega = sqrt(f / c_T,i): every efficiency 1. It knows nothing
// of s_i or eta_i. docs/multi-arm-model.md, "Simulator".
#pragma once

#include "controller/controller_params.h"
#include "controller/multi_arm_law.h"
#include "controller/reference_point.h"
#include "controller/wrench_allocation.h"
#include "model/multi_arm_linearization.h"
#include "model/multi_arm_plant.h"
#include "model/vehicle_description.h"

namespace birotor {

class MultiArmAutopilot {
 public:
  // gains: ControllerParams; hover: SolveMultiArmHover(vehicle)
  // (MultiArmLaw's constructor).
  MultiArmAutopilot(const VehicleDescription& vehicle, const ControllerParams& gains, const MultiArmHover& hover);

  // One control period (1 / rate_hz) of MultiArmLaw::Update on the plant
  // state's x, z, phi and their rates, nominal efficiencies.
  MultiArmRotorCommand Update(const MultiArmPlantState& state, const ReferencePoint& reference);

  MultiArmControlMode mode() const { return law_.mode(); }

 private:
  VehicleDescription vehicle_;
  MultiArmLaw law_;
};

}  // namespace birotor
