// Loading a scenario from YAML with every key validated (unknown keys, ranges,
// rates that are not a whole number of steps, fault times past the end), plus
// command-line overrides "section.key=value" applied on top of the file.
#pragma once

#include <string>
#include <vector>

#include "params/yaml_reader.h"
#include "simulator/scenario.h"

namespace birotor {

// Loads file, applies overrides ("sensors.strain.noise_rad=0", the value is
// YAML: "faults.strain_nan_times_s=[8.0]" works), validates. Throws
// ParamError with a one-line message naming the file and the key.
// arm_count (2 .. kMaxArms) is the vehicle's: the per-arm lists of gauge:
// and faults.initial_thrust_scale hold that many numbers (or two equal
// ones, which every arm takes) and faults.thrust_steps[k].rotor lies in
// [1, arm_count]; Scenario::arm_count records it.
Scenario LoadScenario(const std::string& file, const std::vector<std::string>& overrides = {},
                      int arm_count = kBirotorArmCount);

// Turns a partial scenario file (same sections and keys, any subset) into
// overrides "section.key=value", one per leaf, to pass to LoadScenario after
// the scenario file: birotor-sim --params FILE. Lists are replaced whole.
// Throws ParamError if the file cannot be read or is not a mapping.
std::vector<std::string> OverridesFromFile(const std::string& file);

// Same from YAML text; file_label is used in messages.
Scenario LoadScenarioFromString(const std::string& text, const std::string& file_label,
                                const std::vector<std::string>& overrides = {}, int arm_count = kBirotorArmCount);

}  // namespace birotor
