// In-place update of the `vehicle:` section of a complete parameter file
// (the estimator's file, a scenario): every vehicle key's value is replaced
// by the new one, and everything else of the text (other sections, comments,
// trailing comments on the key lines, key order) is kept. Used by
// `birotor-identify --update-params` for one-step deployment.
#pragma once

#include <string>

#include "model/vehicle_params.h"

namespace birotor {

// The comment line that stamps an identification in the vehicle section:
// "  # identified <stamp>" right below `vehicle:`.
constexpr const char* kIdentificationStampPrefix = "# identified ";

// Returns `text` with the value of every key of the `vehicle:` section
// (VehicleKeys() plus gauge_scale and gauge_offset_rad) set to `params`, and
// the identification stamp line set to `stamp` (replaced when present,
// inserted below `vehicle:` otherwise; no stamp line when empty). False (with
// *error naming the key) when the section or one of its keys is missing.
bool UpdateVehicleSection(const std::string& text, const VehicleParams& params, const std::string& stamp,
                          std::string* updated, std::string* error);

// The identification stamp of a parameter file's vehicle section, or an
// empty string when it has none (or the file cannot be read).
std::string ReadIdentificationStamp(const std::string& file);

}  // namespace birotor
