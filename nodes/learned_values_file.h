// What `birotor-identify --learned FILE` reads: the slow vehicle parameters
// the estimator learned in flight (issue 27 item 2), from its gauge state
// file (the strain scales and the tip mass, written at a clean stop,
// authenticated under the site key) or from an LCM log of the flight (its newest ESTIMATOR_STATUS
// with a learned value: the strain scales and the body mass). A recorded
// status is not authenticated (issue 37 item 4: anyone on the bus can
// publish one), so it is only compared with what a re-run of the log's own
// inputs learns (replay/learned_rerun.h); it is never deployed.
#pragma once

#include <string>
#include <vector>

#include "params/learned_parameter_update.h"
#include "security/message_authenticator.h"

namespace birotor {

// True when path opens as an LCM log (it starts with an event's sync word).
bool IsLcmLog(const std::string& path);

// The strain scales and tip mass of the gauge state file at path, whose mac line must
// verify under the site key (authenticator). False with a one-line *error
// naming the file and the reason: not a gauge state file (", nor an LCM
// log"), not authenticated (no mac line, or a mac that does not verify:
// forged, altered, another key), corrupt, or written for another vehicle
// than vehicle_checksum (VehicleChecksum, gauge_state_file.h).
bool ReadLearnedState(const std::string& path, const std::string& vehicle_checksum,
                      const MessageAuthenticator& authenticator, LearnedVehicleValues* learned, std::string* error);

// The newest ESTIMATOR_STATUS with a learned value on prefix's channel of
// the log at path, as recorded (unauthenticated: for comparison only), and
// the vehicle checksum it names. False with a one-line *error naming the file
// when it is not a readable log or has no such message (learning off, or
// another prefix).
bool ReadRecordedLearnedValues(const std::string& path, const std::string& prefix, LearnedVehicleValues* recorded,
                               std::string* vehicle_checksum, std::string* error);

// Where a recorded learned value disagrees with the re-run's.
struct LearnedDisagreement {
  std::string field;  // "strain_scale[0]", "strain_scale[1]", "body_mass_kg", "tip_mass_kg"
  double recorded = 0, recorded_std = 0;
  bool rerun_learned = false;  // false: the re-run did not learn this field at all
  double rerun = 0, rerun_std = 0;
  double sigmas = 0;  // |recorded - rerun| / sqrt(recorded_std^2 + rerun_std^2)
};

// Every field the recorded status learned that the re-run either did not
// learn or learned more than max_sigmas combined sigmas away:
// |x_rec - x_rerun| > max_sigmas sqrt(s_rec^2 + s_rerun^2).
std::vector<LearnedDisagreement> CompareLearnedValues(const LearnedVehicleValues& recorded,
                                                      const LearnedVehicleValues& rerun, double max_sigmas = 3.0);

// "strain_scale[0]: the log's ESTIMATOR_STATUS says 1.08 +- 0.001, its inputs
// re-run give 0.6852 +- 0.0224 (17.6 combined sigmas apart): the recorded
// status was not used"
std::string DisagreementText(const LearnedDisagreement& disagreement);

}  // namespace birotor
