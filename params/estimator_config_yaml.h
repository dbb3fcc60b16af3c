// Reads and validates an estimator parameter file (config/estimator.yaml):
// the `vehicle:` section into BirotorParams and the `estimator:` section into
// the options of EstimatorConfig. Errors name the file, the key and the range.
#pragma once

#include <string>

#include "estimator/estimator_config.h"
#include "params/yaml_reader.h"

namespace birotor {

// Reads every key of the `estimator:` section into *config; each key is
// required and range-checked, unknown keys are errors. Throws ParamError.
void ReadEstimatorOptions(YamlSection section, EstimatorConfig* config);

// Loads `vehicle:` and `estimator:` from a file, both complete (the shipped
// config/estimator.yaml has every key at its documented default); any other
// top-level key is an error. Throws ParamError naming the file and every
// missing key.
EstimatorConfig LoadEstimatorConfig(const std::string& file);

// Same from YAML text (file is only used in messages).
EstimatorConfig ParseEstimatorConfig(const std::string& text, const std::string& file);

}  // namespace birotor
