// birotor-identify --learned: the learned values that may be deployed, and
// only those (issue 37 item 4). A gauge state file counts only when its mac
// verifies under the site key; from a flight log, only what a re-run of the
// estimator over the log's own inputs learns (replay/learned_rerun.h) is
// deployed, and the log's recorded ESTIMATOR_STATUS (anyone on the bus can
// publish one) is compared with it and reported where it disagrees. The
// tip mass the log's ESTIMATOR_LEARNED_N recorded (nodes/recorded_tip_mass.h)
// is checked like the state file's (another vehicle, out of range: refused)
// and deployed in place of the re-run's when the re-run learned it too and
// the recorded value lies within 3 of the re-run's sigmas with no wider
// sigma (a flight resumed from the state file flew earlier flights'
// readings too); else the re-run's, with a warning. A vehicle with N arms
// (--vehicle) deploys from its own authenticated state file only.
#pragma once

#include <string>

#include "estimator/multi_arm_gauge_state.h"
#include "model/birotor_params.h"
#include "model/vehicle_description.h"
#include "params/learned_parameter_update.h"

namespace birotor {

struct LearnedSourceOptions {
  std::string learned;  // --learned: a gauge state file or an LCM log of the flight
  std::string prefix;   // channel prefix of the log
  // --site-key: the key of the state file's mac (the estimator's default).
  std::string site_key_file = "/etc/birotor/keys/site.key";
  // --estimator-config: the estimator file the log's inputs are re-run with
  // (its estimator: section; learn_strain_scale / learn_body_mass say what is
  // learned). Empty: the shipped estimator.yaml (FindConfigFile).
  std::string estimator_config;
  double min_usable_fraction = 0;  // --min-usable-fraction of the log
};

// Reads options.learned into *learned, relative to `vehicle` (the vehicle
// section of the --update-params file, named update_params); logs the
// warnings (recorded values not used, a damaged log). Returns a one-line
// error naming the file and the reason, empty on success.
std::string ReadTrustedLearnedValues(const LearnedSourceOptions& options, const BirotorParams& vehicle,
                                     const std::string& update_params, LearnedVehicleValues* learned);

// For a vehicle with N arms (--vehicle): its gauge state file
// (nodes/vehicle_state_file.h) read into *state, its mac verified under the
// site key, written for this description (DescriptionChecksum of `vehicle`,
// the one being updated) and its arm count; a flight log is refused. Returns
// the same one-line refusals as above, empty on success.
std::string ReadTrustedVehicleState(const LearnedSourceOptions& options, const VehicleDescription& vehicle,
                                    MultiArmGaugeState* state);

}  // namespace birotor
