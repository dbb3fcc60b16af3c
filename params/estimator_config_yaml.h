// Reads and validates an estimator parameter file (config/estimator.yaml):
// the `vehicle:` section into VehicleParams and the `estimator:` section into
// the options of EstimatorConfig. Errors name the file, the key and the range.
#pragma once

#include <string>

#include "estimator/estimator_config.h"
#include "params/yaml_reader.h"

namespace birotor {

// Overrides the fields of *config present in the `estimator:` section; every
// key is range-checked, unknown keys are errors. Throws ParamError.
void ReadEstimatorOptions(YamlSection section, EstimatorConfig* config);

// Loads `vehicle:` (optional, defaults: reference vehicle) and `estimator:`
// (optional, defaults as documented in estimator_config.h) from a file;
// any other top-level key is an error. Throws ParamError.
EstimatorConfig LoadEstimatorConfig(const std::string& file);

// Same from YAML text (file is only used in messages).
EstimatorConfig ParseEstimatorConfig(const std::string& text, const std::string& file);

}  // namespace birotor
