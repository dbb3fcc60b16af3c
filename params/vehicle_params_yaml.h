// Reads and validates the `vehicle:` section of a parameter file into
// VehicleParams (defaults: the reference vehicle), and writes it back.
#pragma once

#include <string>

#include "model/vehicle_params.h"
#include "params/yaml_reader.h"

namespace birotor {

// Overrides the fields of *params present in the section; every key is
// range-checked (masses and stiffness strictly positive). Unknown keys are
// errors.
void ReadVehicleParams(YamlSection section, VehicleParams* params);

// Loads `vehicle:` from a file; throws ParamError.
VehicleParams LoadVehicleParams(const std::string& file);

// YAML text of a `vehicle:` section (full precision), for identification output.
std::string VehicleParamsYaml(const VehicleParams& params, const std::string& indent = "  ");

}  // namespace birotor
