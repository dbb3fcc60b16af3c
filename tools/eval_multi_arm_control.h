// birotor-eval --control-vehicle FILE: the product's N-rotor controller
// (controller/multi_arm_controller.h) flown lock-step on a vehicle
// description (evaluation/multi_arm_closed_loop.h) over the lateral step,
// the aggressive move and a 40 % thrust loss on each rotor, with the cascade
// and in mode mpc (the N-input MPC, the cascade its fallback), each with the
// nominal map; the loss cases also with each rotor's true efficiency (the
// bound an efficiency estimate can reach). docs/controller.md, "Vehicles with N rotors".
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace birotor {

struct MultiArmControlCli {
  std::string vehicle_file;  // --control-vehicle; empty: not this mode
};

// Adds --control-vehicle to birotor-eval's command line.
void AddMultiArmControlOptions(CLI::App& app, MultiArmControlCli* cli);

// What the mode takes from birotor-eval's other options.
struct MultiArmControlInputs {
  std::vector<std::string> cases;      // --scenarios; empty: the default cases
  std::string controller_params;       // --controller-params
  std::string scenario_dir;            // --scenario-dir ("" : the config search path)
  std::vector<std::string> overrides;  // --set, after each case's own
  std::string markdown_out;            // --markdown-out ("" : none)
};

// Prints the table; 0, or kExitFailure when a file cannot be loaded or
// written, or a command left [0, omega_max].
int RunMultiArmControl(const MultiArmControlCli& cli, const MultiArmControlInputs& inputs);

}  // namespace birotor
