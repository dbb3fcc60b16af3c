// The tip mass a flight log recorded (issue 36 item 4): the estimator
// publishes the m_p it flies, its sigma and its source on every
// ESTIMATOR_LEARNED_N; `birotor-identify --learned LOG` reads the newest
// learned one (source learned or state_file: a flight that resumed from the
// state file flew an m_p a re-run of its inputs alone cannot reproduce) and
// checks it as the state file's tip mass is checked: the vehicle it was
// flown with, the ranges. The message is not authenticated, so the tool
// deploys it only where the log's own inputs support it
// (tools/identify_learned_source.h).
#pragma once

#include <cstdint>
#include <string>

#include "model/vehicle_description.h"

namespace birotor {

struct RecordedTipMass {
  double tip_mass_kg = 0;        // m_p of the arms (the birotor flies one for both) [kg]
  double tip_mass_std_kg = 0;    // its one sigma [kg]
  double other_arm_kg = 0;       // arm 2's, which must be arm 1's [kg]
  std::string source;            // "learned" or "state_file"
  std::string vehicle_checksum;  // DescriptionChecksum of the vehicle it was flown with
  int64_t utime = 0;             // of the message [us]
  int32_t n_arms = 0;
};

// The newest ESTIMATOR_LEARNED_N on `channel` of the LCM log at log_path
// whose tip_mass_source is learned or state_file. False with a one-line
// *error naming the file when the log is not readable or holds none (tip
// mass learning off, a log older than the type, another prefix).
bool ReadRecordedTipMass(const std::string& log_path, const std::string& channel, RecordedTipMass* recorded,
                         std::string* error);

// "" when the recorded tip mass may be deployed into `vehicle` (the vehicle
// of the --update-params file update_params), else the refusal, one line
// naming the log and the key: flown with another vehicle or parameter file
// (DescriptionChecksum), not one m_p for both arms, or tip_mass_kg /
// tip_mass_std_kg outside the state file's ranges (LearnedTipMassRangeProblem).
std::string RecordedTipMassRefusal(const std::string& log_path, const RecordedTipMass& recorded,
                                   const VehicleDescription& vehicle, const std::string& update_params);

}  // namespace birotor
