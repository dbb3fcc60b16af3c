// Reads and validates the controller parameter file (config/controller.yaml):
// the `vehicle:` section (the controller's model of the vehicle), the
// `controller:` section and the `mpc:` section (MpcParams) into ControllerConfig, and the gain keys shared with
// the `controller:` section of a scenario (the simulator's autopilot).
// Errors name the file, the key and the allowed range.
#pragma once

#include <string>

#include "controller/controller_params.h"
#include "params/yaml_reader.h"

namespace birotor {

// The gains of the position/pitch law, every key but rate_hz (whose allowed
// values depend on the caller: the simulator needs a whole number of steps).
void ReadControllerGains(YamlSection& section, ControllerParams* gains);

// Loads `vehicle:` and `controller:` from a file, both complete; any other
// top-level key is an error. Throws ParamError naming the file and every
// missing key.
ControllerConfig LoadControllerConfig(const std::string& file);
// Same from YAML text (file is only used in messages).
ControllerConfig ParseControllerConfig(const std::string& text, const std::string& file);

}  // namespace birotor
