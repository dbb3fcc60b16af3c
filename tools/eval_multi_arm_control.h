// birotor-eval --vehicle FILE --control: the product's N-rotor controller
// (controller/multi_arm_controller.h) flown lock-step on a vehicle
// description (evaluation/multi_arm_closed_loop.h) over the lateral step,
// the aggressive move, a 40 % thrust loss on each rotor and every rotor at
// 0.85 of its map from the start (density85: EfficiencyConditioner's
// absolute rule), with the cascade
// and in mode mpc (the N-input MPC, the cascade its fallback), each with the
// nominal map and with force feedback on the N-arm estimator's efficiencies
// (evaluation/estimated_efficiency_provider.h: the product path); the loss
// cases also with each rotor's true efficiency (the bound an efficiency
// estimate can reach). Cases descentPP_rotorK (a climb to 1 m, rotor K at
// (100 - PP) % from 5 s) add a table of the controlled descent: entries, h
// and v at its start, the level floor, the touchdown at the take-off level
// and the peak tilt (evaluation/multi_arm_descent_floor.h). docs/
// controller.md, "Vehicles with N rotors" and "Degrading with N rotors".
#pragma once

#include <string>
#include <vector>

#include "estimator/estimator_config.h"

namespace birotor {

// What the mode takes from birotor-eval's options.
struct MultiArmControlInputs {
  std::string vehicle_file;            // --vehicle
  std::vector<std::string> cases;      // --scenarios; empty: the default cases
  std::string controller_params;       // --controller-params
  std::string scenario_dir;            // --scenario-dir ("" : the config search path)
  std::vector<std::string> overrides;  // --set, after each case's own
  std::string markdown_out;            // --markdown-out ("" : none)
  EstimatorConfig estimator;           // --params: the N-arm estimator's ekf: and pipeline: sections
};

// Prints the table; 0, or kExitFailure when a file cannot be loaded or
// written, or a command left [0, omega_max].
int RunMultiArmControl(const MultiArmControlInputs& inputs);

}  // namespace birotor
