// The newest learned tip mass of a flight log's ESTIMATOR_LEARNED_N.
#include "nodes/recorded_tip_mass.h"

#include <cstdio>

#include "birotor/estimator_learned_n_t.hpp"
#include "model/vehicle_description_checksum.h"
#include "nodes/gauge_state_file.h"
#include "nodes/status_message.h"
#include "transport/lcm_codec.h"
#include "transport/log_io.h"

namespace birotor {
namespace {

bool LearnedTipMass(const estimator_learned_n_t& message) {
  return (message.tip_mass_source == kLearnedSourceLearned || message.tip_mass_source == kLearnedSourceStateFile) &&
         message.n_arms >= 1 && message.tip_mass_kg.size() == static_cast<size_t>(message.n_arms) &&
         message.tip_mass_std_kg.size() == message.tip_mass_kg.size();
}

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.10g", value);
  return text;
}

}  // namespace

bool ReadRecordedTipMass(const std::string& log_path, const std::string& channel, RecordedTipMass* recorded,
                         std::string* error) {
  LogReader reader;
  if (!reader.Open(log_path, error)) return false;
  LogEvent event;
  estimator_learned_n_t message;
  int64_t messages = 0, undecodable = 0, found = 0;
  while (reader.Next(&event)) {
    if (event.channel != channel) continue;
    ++messages;
    if (DecodeMessage(event.data.data(), event.data.size(), &message) != DecodeError::kNone) {
      ++undecodable;
      continue;
    }
    if (!LearnedTipMass(message)) continue;
    recorded->tip_mass_kg = message.tip_mass_kg[0];
    recorded->tip_mass_std_kg = message.tip_mass_std_kg[0];
    recorded->other_arm_kg = message.tip_mass_kg.back();
    recorded->source = message.tip_mass_source;
    recorded->vehicle_checksum = message.vehicle_checksum;
    recorded->utime = message.utime;
    recorded->n_arms = message.n_arms;
    ++found;
  }
  if (found == 0) {
    *error = log_path + ": no " + channel + " message with a learned tip_mass_kg (" + std::to_string(messages) +
             " messages, " + std::to_string(undecodable) +
             " undecodable; the estimator learns it with model_consistency arm_mode_learn_tip_mass on)";
    return false;
  }
  return true;
}

std::string RecordedTipMassRefusal(const std::string& log_path, const RecordedTipMass& recorded,
                                   const VehicleDescription& vehicle, const std::string& update_params) {
  const std::string where = "--learned " + log_path + ": its newest ESTIMATOR_LEARNED_N with a learned tip_mass_kg ";
  const std::string checksum = DescriptionChecksum(vehicle);
  if (recorded.vehicle_checksum != checksum) {
    return where + "was flown with another vehicle or parameter file (vehicle checksum '" + recorded.vehicle_checksum +
           "', " + update_params + " now " + checksum + "): not deployed, nothing written";
  }
  if (recorded.n_arms != vehicle.arm_count || recorded.other_arm_kg != recorded.tip_mass_kg) {
    return where + "is not one m_p for both arms (" + Number(recorded.tip_mass_kg) + ", " +
           Number(recorded.other_arm_kg) + " kg): not deployed, nothing written";
  }
  const std::string problem = LearnedTipMassRangeProblem(recorded.tip_mass_kg, recorded.tip_mass_std_kg);
  if (!problem.empty()) return where + "has " + problem + ": refused, nothing written";
  return "";
}

}  // namespace birotor
