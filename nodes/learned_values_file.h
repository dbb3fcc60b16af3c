// What `birotor-identify --learned FILE` reads: the slow vehicle parameters
// the estimator learned in flight (issue 27 item 2), from its gauge state
// file (the strain scales, written at a clean stop) or from an LCM log of the
// flight (the newest ESTIMATOR_STATUS with a learned value: the strain scales
// and the body mass). Either names the vehicle section the values are
// relative to; a file for another vehicle is refused.
#pragma once

#include <string>

#include "params/learned_parameter_update.h"

namespace birotor {

// Reads path (an LCM log when it starts with an event's sync word, a gauge
// state file otherwise) into *learned. prefix: the channel prefix of the
// log's ESTIMATOR_STATUS. False with a one-line *error naming the file when
// it cannot be read, holds nothing learned, or was written for another
// vehicle than vehicle_checksum (VehicleChecksum, gauge_state_file.h).
bool ReadLearnedValues(const std::string& path, const std::string& prefix, const std::string& vehicle_checksum,
                       LearnedVehicleValues* learned, std::string* error);

}  // namespace birotor
