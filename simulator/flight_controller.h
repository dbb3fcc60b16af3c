// The simulator's autopilot: the shared cascaded position/pitch law of
// controller/position_attitude_law.h on the TRUE rigid-body state (a perfect
// state estimate), turned into rotor speeds through the NOMINAL thrust map
// omega = sqrt(f / c_T). It knows nothing of s_i or eta_i.
#pragma once

#include "controller/position_attitude_law.h"
#include "model/plant.h"
#include "samples/rotor_count.h"
#include "simulator/scenario.h"
#include "simulator/trajectory.h"

namespace birotor {

struct RotorCommand {
  double omega_cmd_rad_s[kBirotorRotors] = {0.0, 0.0};
};

class FlightController {
 public:
  // hover_force_n: per-rotor feed-forward thrust at hover (the equilibrium
  // solution of the nominal vehicle).
  FlightController(const BirotorParams& vehicle, const ControllerParams& params, double hover_force_n);

  // One control period (1 / rate_hz) of PositionAttitudeLaw on the plant state.
  RotorCommand Update(const PlantState& state, const ReferencePoint& reference);

 private:
  BirotorParams vehicle_;
  PositionAttitudeLaw law_;
};

}  // namespace birotor
