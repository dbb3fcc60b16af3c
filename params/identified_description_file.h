// Output of the N-arm bench or flight identification (identification/
// multi_arm_bench_fit.h, multi_arm_flight_fit.h): the identified vehicle description in the N-arm
// form of config/vehicles/trirotor.yaml (every key, read back by
// LoadVehicleDescription), each fitted value with its one sigma as a
// comment, an undetermined one marked and left at the base file's value.
#pragma once

#include <string>
#include <vector>

#include "identification/multi_arm_bench_fit.h"

namespace birotor {

// YAML text: a comment header (sources, the calibration fact held, every
// arm's residual RMS), then `vehicle:` with the body keys and `arms:`;
// each fitted key ends in "# +- SIGMA" or "# NOT DETERMINED by these logs:
// value of the base file". Numbers at full precision (max_digits10), so
// reading the text back gives result.vehicle exactly.
std::string IdentifiedDescriptionYaml(const MultiArmIdentificationResult& result,
                                      const std::vector<std::string>& sources);

}  // namespace birotor
