// Reads a vehicle description (model/vehicle_description.h) from the
// `vehicle:` section of a file, in either of its two forms
// (docs/vehicle-description.md): the N-arm form, body keys and `arms:` a list
// of maps, or the birotor form of config/reference_vehicle.yaml, read as N = 2.
// A description that cannot fly is refused where it is read.
#pragma once

#include <string>

#include "model/vehicle_description.h"
#include "params/yaml_reader.h"

namespace birotor {

// Reads the `vehicle:` section (passed as section) in either form; every key
// is required, ranges are those of the birotor keys (VehicleKeys), unknown
// keys are errors, a section with both forms is refused naming both, and a
// complete description must pass CheckPlausible.
void ReadVehicleDescription(YamlSection section, VehicleDescription* description);

// For a room whose model is the birotor's (the estimator, the controller),
// after the whole file has been read: a description that is not a birotor
// (ToBirotorParams) is refused with ParamError "<file>: key 'vehicle': <who>
// runs the birotor's model ...: <why>".
void RequireBirotor(const std::string& file, const std::string& who, const VehicleDescription& description);

// Loads `vehicle:` from a file (other top-level sections are allowed);
// ParamError names the file, the key and the allowed range, or why the
// vehicle cannot fly.
VehicleDescription LoadVehicleDescription(const std::string& file);
// The same from text already read (file names it in messages), for a file
// read once and then updated in place (birotor-identify --update-params).
VehicleDescription ParseVehicleDescription(const std::string& text, const std::string& file);

// Whether the `vehicle:` section of text is in the N-arm form (it has
// `arms:`); false for the birotor form and for text that does not parse.
bool IsArmsForm(const std::string& text);

// ParamError "<file>: key '<section>': the vehicle cannot fly: <problem>; ..."
// when PlausibilityProblems(description) is not empty.
void CheckPlausible(const YamlSection& section, const VehicleDescription& description);

}  // namespace birotor
