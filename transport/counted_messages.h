// The counted wire types (the _n_t types of lcmtypes/, for a vehicle with N
// arms, docs/interface.md "Vehicles with N arms"): the receiver's check of
// their count against its own vehicle description, the birotor messages read
// as the counted ones with N = 2 (so an old log goes through the new path),
// and the description itself on the wire (VEHICLE_DESCRIPTION).
#pragma once

#include <cstdint>
#include <string>

#include "birotor/force_estimate_n_t.hpp"
#include "birotor/force_estimate_t.hpp"
#include "birotor/loadcell_n_t.hpp"
#include "birotor/loadcell_t.hpp"
#include "birotor/motor_command_n_t.hpp"
#include "birotor/motor_command_t.hpp"
#include "birotor/motor_n_t.hpp"
#include "birotor/motor_t.hpp"
#include "birotor/strain_n_t.hpp"
#include "birotor/strain_t.hpp"
#include "birotor/truth_n_t.hpp"
#include "birotor/truth_t.hpp"
#include "birotor/vehicle_description_t.hpp"
#include "model/vehicle_description.h"
#include "samples/multi_arm_samples.h"

namespace birotor {

// What a receiver thinks of a counted message's count.
enum class CountCheck {
  kMatches,       // the count is the description's arm_count and every array holds it
  kOutOfRange,    // the count is outside [2, kMaxArms] (0, 7, negative): no vehicle has it
  kMismatch,      // a vehicle's count, not the receiver's: another description
  kInconsistent,  // an array whose length is not the count, or a rotor fault bit at or
                  // beyond it (a message built in memory; decoded ones cannot have short arrays)
};

// Stable lower-case name for counters and log lines ("out_of_range", ...).
const char* CountCheckName(CountCheck check);

// A receiver's refusals of counted messages, since start-up, by reason (an
// input's counters; the caller publishes them in its status).
struct CountRefusals {
  int64_t out_of_range = 0;
  int64_t mismatch = 0;
  int64_t inconsistent = 0;

  int64_t Total() const { return out_of_range + mismatch + inconsistent; }
  // Counts check under its reason; kMatches counts nothing.
  void Count(CountCheck check);
};

// The check of one message against the receiver's description: arm i of the
// message is arm i of the description only when the counts agree, so any
// other count is refused (never truncated or padded).
CountCheck CheckCount(const strain_n_t& message, const VehicleDescription& description);
CountCheck CheckCount(const motor_n_t& message, const VehicleDescription& description);
CountCheck CheckCount(const loadcell_n_t& message, const VehicleDescription& description);
CountCheck CheckCount(const truth_n_t& message, const VehicleDescription& description);
CountCheck CheckCount(const force_estimate_n_t& message, const VehicleDescription& description);
CountCheck CheckCount(const motor_command_n_t& message, const VehicleDescription& description);

// True when CheckCount says kMatches; otherwise counts the refusal in
// *refusals (may be null) and returns false: the caller drops the message.
template <class CountedMessage>
bool CountMatches(const CountedMessage& message, const VehicleDescription& description, CountRefusals* refusals) {
  const CountCheck check = CheckCount(message, description);
  if (refusals != nullptr) refusals->Count(check);
  return check == CountCheck::kMatches;
}

// A birotor message as its counted twin with N = 2, field for field (the
// birotor's arm 1 and 2 are the counted arms 1 and 2). force_estimate_t's
// STATUS_ROTOR1_FAULT / STATUS_ROTOR2_FAULT become rotor_fault_bits 0 and 1;
// every other status bit keeps its value.
strain_n_t ToCountedMessage(const strain_t& message);
motor_n_t ToCountedMessage(const motor_t& message);
loadcell_n_t ToCountedMessage(const loadcell_t& message);
truth_n_t ToCountedMessage(const truth_t& message);
force_estimate_n_t ToCountedMessage(const force_estimate_t& message);
motor_command_n_t ToCountedMessage(const motor_command_t& message);

// The reverse, for a counted message of a birotor: false, *out untouched,
// unless the count is 2 and the message is consistent (CheckCount's
// kInconsistent cases). ToBirotorMessage(ToCountedMessage(m)) is m, bytewise.
bool ToBirotorMessage(const strain_n_t& message, strain_t* out);
bool ToBirotorMessage(const motor_n_t& message, motor_t* out);
bool ToBirotorMessage(const loadcell_n_t& message, loadcell_t* out);
bool ToBirotorMessage(const truth_n_t& message, truth_t* out);
bool ToBirotorMessage(const force_estimate_n_t& message, force_estimate_t* out);
bool ToBirotorMessage(const motor_command_n_t& message, motor_command_t* out);

// The N-arm samples (samples/multi_arm_samples.h) on the wire: arrays of
// n_arms (n_rotors) entries, every other field as it is.
strain_n_t ToMessage(const MultiArmStrainSample& sample);
motor_n_t ToMessage(const MultiArmMotorSample& sample);
loadcell_n_t ToMessage(const MultiArmLoadCellSample& sample);
truth_n_t ToMessage(const MultiArmTruthSample& sample);
// The N-arm EKF's estimate (estimator/multi_arm_ekf.h) as FORCE_N.
force_estimate_n_t ToMessage(const MultiArmForceEstimate& estimate);
// The same into *message, reusing its vectors (no allocation once they hold N).
void ToMessage(const MultiArmForceEstimate& estimate, force_estimate_n_t* message);
// A decoded counted sample (the count checked by CheckCount first): entries
// beyond kMaxSampleArms are dropped, those beyond the count stay zero.
void FromMessage(const strain_n_t& message, MultiArmStrainSample* sample);
void FromMessage(const motor_n_t& message, MultiArmMotorSample* sample);
void FromMessage(const loadcell_n_t& message, MultiArmLoadCellSample* sample);
void FromMessage(const truth_n_t& message, MultiArmTruthSample* sample);
void FromMessage(const force_estimate_n_t& message, MultiArmForceEstimate* estimate);

// The description a program runs with, for VEHICLE_DESCRIPTION: every field,
// the checksum (DescriptionChecksum), publisher the program's name; utime and
// seq are the caller's. arm_count must be in [2, kMaxArms] (a loaded
// description is).
vehicle_description_t ToMessage(const VehicleDescription& description, const std::string& publisher);

// The description a log or another program says it ran with: false, with
// *why, when the count is outside [2, kMaxArms], an array does not hold the
// count, or the checksum is not the one of the fields (a corrupt or
// hand-made message). On success DescriptionChecksum(*out) == message.checksum.
bool FromMessage(const vehicle_description_t& message, VehicleDescription* out, std::string* why);

}  // namespace birotor
