// What the two gauge state files share (the birotor's, nodes/gauge_state_file.h,
// and the one of a vehicle with N arms, nodes/vehicle_state_file.h): the
// size limit, reading without following a link, the checksum line, the
// mac line under the site key, the value ranges taken from the vehicle keys,
// and the check that a path about to be replaced holds a state file of the
// same kind. Each file starts with its own header line, so neither reader
// ever takes the other's file for its own.
#pragma once

#include <cstddef>
#include <map>
#include <string>

#include "params/regular_file.h"
#include "security/message_authenticator.h"

namespace birotor {

// A state file is a few hundred bytes; anything larger is not one.
inline constexpr size_t kMaxStateFileBytes = 4096;

// The first line of each kind of state file.
inline constexpr const char* kBirotorStateHeader = "# birotor-estimator gauge offset state\n";
inline constexpr const char* kVehicleStateHeader = "# birotor-estimator gauge offset state, N arms\n";

// What text is, by its first line: the birotor's state file, an N-arm
// vehicle's, or neither.
enum class StateFileKind { kBirotor, kVehicle, kNone };
StateFileKind StateFileKindOf(const std::string& text);
// "a birotor gauge state file (birotor-estimator without --vehicle)" and
// "a gauge state file of a vehicle with N arms (birotor-estimator --vehicle)".
const char* StateFileKindName(StateFileKind kind);

// A closed range of a persisted value.
struct StateValueRange {
  double min;
  double max;
};
// The range of a vehicle key of the birotor parameter table
// (params/birotor_params_yaml.cc VehicleKeys: gauge_offset_std_rad,
// tip_mass_kg, ...); {0, 0} for a name not in it.
StateValueRange VehicleKeyRange(const char* name);
// The allowed one sigma of a persisted gauge offset: the range of the
// vehicle key gauge_offset_std_rad [rad].
StateValueRange GaugeOffsetStdRange();

// Exactly n finite numbers separated by spaces, from text into out[0..n);
// false otherwise (out then partly written).
bool ParseFiniteNumbers(const std::string& text, int n, double* out);

// The mac line of text: "mac: <64 hex>\n", HMAC-SHA-512-256 under the site
// key (MessageAuthenticator, counter 0) of all of text.
std::string StateFileMacLine(const std::string& text, const MessageAuthenticator& authenticator);
// Where the last line of text starts if it is a mac line; npos otherwise.
size_t StateFileMacLineStart(const std::string& text);
// Checks the mac line of *text under the site key and strips it; false with
// a one-line *error ("<path>: not authenticated (...)") otherwise.
bool VerifyStateFileMac(const std::string& path, const MessageAuthenticator& authenticator, std::string* text,
                        std::string* error);

// Reads the state file at path (a regular file, no link, at most
// kMaxStateFileBytes) into *text, without its mac line. authenticator null:
// a mac line is stripped unchecked; else it must be there and verify.
bool ReadStateFileText(const std::string& path, const MessageAuthenticator* authenticator, std::string* text,
                       std::string* error);

// The body of text (every line before the checksum line) after its
// checksum verified, as "key: value" fields (comment lines left out). False
// with *error "<path>: corrupt (...)" when the first line is not header or
// the checksum line is missing or does not match; a state file of the
// other kind is named as such.
bool ChecksummedStateFields(const std::string& path, const std::string& text, const char* header,
                            std::map<std::string, std::string>* fields, std::string* error);

// Whether path may be replaced by a state file of header's kind: absent
// (*attributes: 0644, the writer's owner) or a regular file starting with
// header (*attributes: its mode and owner). Else false, *error "<path>:
// exists and is ...: not overwritten" (a link, a FIFO, another file such as
// the parameter file, or the other kind of state file).
bool ReplaceableStateFile(const std::string& path, const char* header, FileAttributes* attributes, std::string* error);

}  // namespace birotor
