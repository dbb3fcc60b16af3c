// Reads and validates the `identification:` section of an identification
// options file (config/identification.yaml) into IdentificationOptions
// (identification/identification_options.h). Errors name the file, the key
// and the range.
#pragma once

#include <string>

#include "identification/identification_options.h"
#include "params/yaml_reader.h"

namespace birotor {

// Reads every field from the section (keys are the field names; each is
// required); unknown keys and values out of range throw ParamError.
void ReadIdentificationOptions(YamlSection section, IdentificationOptions* options);

// Loads the `identification:` section of a file (config/identification.yaml
// has every key at its default); throws ParamError naming the file and every
// missing key.
IdentificationOptions LoadIdentificationOptions(const std::string& file);

}  // namespace birotor
