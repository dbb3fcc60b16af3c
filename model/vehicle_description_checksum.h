// Which vehicle description a program ran with, in 16 hex digits: the
// checksum that travels in VEHICLE_DESCRIPTION (lcmtypes/vehicle_description_t.lcm)
// so a log says which description it was recorded with. The same method as
// the birotor parameter checksum of ESTIMATOR_STATUS (FNV-1a 64 of a
// canonical text, numerics/fnv1a.h), over every field of the description.
#pragma once

#include <string>

#include "model/vehicle_description.h"

namespace birotor {

// One line "key: value" per field, in the order of vehicle_description.h:
// name, arm_count, the body fields, then arms[i].<field> for i in
// [0, arm_count) (the unused arms[arm_count ..] are not part of the
// description). Reals in the shortest form that reads back to the same
// double (std::to_chars: locale-free, the same text on every machine),
// angles in radians, booleans as true/false. Starts with a version line, so
// a change of this text is a new version, never a silent change of every
// checksum.
std::string DescriptionCanonicalText(const VehicleDescription& description);

// FNV-1a 64 of DescriptionCanonicalText, 16 lower-case hex digits. Equal
// descriptions (bit for bit) give equal checksums; any changed field changes
// it (up to FNV's 2^-64 chance of a collision). Not a defence against a
// forged file.
std::string DescriptionChecksum(const VehicleDescription& description);

}  // namespace birotor
