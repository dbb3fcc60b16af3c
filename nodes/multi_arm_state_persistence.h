// The N-arm daemon's gauge state file at its start and its clean stop
// (birotor-estimator --vehicle, estimator.tare.state_file): the file's
// offsets and learned tip mass into the node before the first packet, and
// what the node holds written back at the stop (nodes/vehicle_state_file.h
// for the file and its checks). Logs one line each, as the birotor daemon.
#pragma once

#include <string>

#include "estimator/estimator_config.h"
#include "nodes/multi_arm_estimator_service.h"
#include "security/message_authenticator.h"

namespace birotor {

// Restores the state file at path into *service: true when it was read and
// used. A missing file is a first start (the description's offsets, one
// info line); a refused one (corrupt, foreign, the birotor's, not
// authenticated, a value out of range) is one warning with its reason, and
// the description's values are flown.
bool RestoreVehicleGaugeState(const std::string& path, const EstimatorConfig& config,
                              const MessageAuthenticator& authenticator, MultiArmEstimatorService* service);

// Writes what *service holds now (MultiArmPipeline::GaugeState) to path; false
// with a one-line *error when the file is refused (WriteVehicleGaugeState).
bool PersistVehicleGaugeState(const std::string& path, const MultiArmEstimatorService& service,
                              const MessageAuthenticator& authenticator, std::string* error);

}  // namespace birotor
