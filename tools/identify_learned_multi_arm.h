// birotor-identify --vehicle DESC --update-params FILE --learned STATE: what
// the estimator of a vehicle with N arms learned in flight (birotor-estimator
// --vehicle; its authenticated gauge state file, nodes/vehicle_state_file.h)
// deployed into the description FILE in place: every arm's tip_mass_kg
// scaled by the learned ratio r. The gauge offsets the file holds are not
// deployed, as the birotor's are not: a power-up value that drifts, which
// the filter's offset states measure at rest at each start
// (docs/identification.md, "Deploying what the estimator learned").
#pragma once

#include <string>

#include "params/learned_parameter_update.h"
#include "params/vehicle_section_update.h"
#include "tools/identify_learned_source.h"

namespace birotor {

struct MultiArmLearnedRequest {
  // --vehicle: the description the estimator flew; it must be the one
  // update_params holds (DescriptionChecksum). Empty: update_params's own.
  std::string vehicle;
  // --update-params: the description updated in place (N-arm or birotor
  // form), with the guarantees of params/vehicle_section_update.h.
  std::string update_params;
  LearnedSourceOptions source;  // --learned (the state file), --site-key
  LearnedDeployOptions deploy;  // --learned-max-std-fraction
  std::string stamp_time;       // the stamp's date, 2026-12-01T02:55:00Z (UTC)
};

// Deploys into `update` (request.update_params, checked and read by
// PrepareParameterFileUpdate, its outputs checked against the inputs):
// reads and checks the state file, applies r, writes the file; logs what was
// deployed with its sigma, what was not and why, and the description's new
// checksum. "" on success, else one line naming the file and the reason;
// nothing written then.
std::string DeployLearnedMultiArm(const MultiArmLearnedRequest& request, const ParameterFileUpdate& update);

}  // namespace birotor
