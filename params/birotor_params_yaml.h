// Reads and validates the `vehicle:` section of a parameter file into
// BirotorParams, and writes it back. The keys, their ranges and their units
// are one table (kVehicleKeys), used by the reader and the writer: a new
// vehicle parameter is one line there plus the key in the shipped files.
#pragma once

#include <string>
#include <vector>

#include "model/birotor_params.h"
#include "params/yaml_reader.h"

namespace birotor {

// One key of the `vehicle:` section: name, allowed range and field.
struct VehicleKey {
  const char* name;
  double min;
  double max;
  double BirotorParams::*field;
};

// The range of each element of gauge_scale [1] (the reader's, and what
// birotor-identify may deploy there).
inline constexpr double kGaugeScaleMin = 0.5;
inline constexpr double kGaugeScaleMax = 2.0;
// The range of each element of gauge_offset_rad, [-max, max] [rad].
inline constexpr double kGaugeOffsetMaxRad = 1e-2;

// Every scalar key of the `vehicle:` section, in file order (the two-element
// gauge_scale and gauge_offset_rad follow them).
const std::vector<VehicleKey>& VehicleKeys();
// The row of VehicleKeys() called name (ParamError-free: a name not in the
// table is a programming error and throws std::logic_error).
const VehicleKey& FindVehicleKey(const std::string& name);

// Reads every key of the section (each is required); ranges are checked
// (masses and stiffness strictly positive). Unknown keys are errors. A
// complete section must also fly: PlausibilityProblems of its
// BirotorDescription (e.g. a hover speed above omega_max) is a ParamError
// naming the file (params/vehicle_description_yaml.h, CheckPlausible).
void ReadBirotorParams(YamlSection section, BirotorParams* params);

// Loads `vehicle:` from a file (other top-level sections are allowed, so an
// estimator file can serve as a vehicle file); throws ParamError naming the
// file and every missing key, or why the vehicle cannot fly.
BirotorParams LoadBirotorParams(const std::string& file);

// YAML text of a `vehicle:` section (full precision), for identification
// output. comments[key] (optional) is appended to that key's line as `# ...`.
std::string BirotorParamsYaml(const BirotorParams& params, const std::string& indent = "  ");
std::string BirotorParamsYaml(const BirotorParams& params,
                              const std::vector<std::pair<std::string, std::string>>& comments,
                              const std::string& indent = "  ");

}  // namespace birotor
