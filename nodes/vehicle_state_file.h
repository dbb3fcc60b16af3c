// The gauge state file of a vehicle with N arms (birotor-estimator --vehicle,
// estimator.tare.state_file): at a clean stop the daemon writes each gauge's
// offset as the N-arm filter knows it, with its sigma, and the tip-mass
// ratio r the arm-mode test learned; the next start flies from them. The
// same protections as the birotor's file (nodes/gauge_state_file.h, the
// shared parts in nodes/state_file_common.h): written through a temporary
// file and a rename, never over anything but a state file of this kind, at
// most 4 kB, a checksum line, the vehicle named by the checksum of its
// description (DescriptionChecksum, the one ESTIMATOR_STATUS carries),
// authenticated under the site key (the mac line), every value range-checked
// on reading. Its own header line: a birotor state file is refused here, and
// this one by the birotor's reader.
#pragma once

#include <string>

#include "estimator/multi_arm_gauge_state.h"
#include "model/vehicle_description.h"
#include "security/message_authenticator.h"

namespace birotor {

// The vehicle checksum a state file of this description carries
// (DescriptionChecksum: FNV-1a 64 of its canonical text, 16 hex digits).
std::string VehicleStateChecksum(const VehicleDescription& vehicle);

// File text (without the mac line) for state:
//   # birotor-estimator gauge offset state, N arms
//   vehicle_checksum: <16 hex>
//   arm_count: <N>
//   gauge_offset_rad: <o_1> ... <o_N>
//   gauge_offset_std_rad: <s_1> ... <s_N>
//   tip_mass_ratio: <r>              (only when learned: m_p,i = r m_p,i of the description)
//   tip_mass_ratio_std: <s>          (its one sigma)
//   checksum: <16 hex of the lines above>
std::string VehicleStateText(const MultiArmGaugeState& state, const std::string& vehicle_checksum);

// Writes the text and its mac line (HMAC under the site key, counter 0, of
// every byte before it) to path through a uniquely named temporary file and
// a rename. Refused (false, *error, nothing written) when path exists and is
// not a state file of this kind (a link, a FIFO, a device, the parameter
// file, the birotor's state file), or when an offset or its sigma is not
// finite. A sigma outside the reader's range is written at its bound; a
// ratio outside it is left out. An existing file keeps its mode and owner; a
// new one is 0644.
bool WriteVehicleGaugeState(const std::string& path, const MultiArmGaugeState& state,
                            const std::string& vehicle_checksum, const MessageAuthenticator& authenticator,
                            std::string* error);

// Reads the file into *state (source kStateFile). False with a one-line
// *error naming the file and the field, *state unchanged, for: a path that
// is not a regular file or larger than 4 kB; no mac line or one that does
// not verify; the birotor's state file; a corrupt file (bad checksum, a
// field missing or not arm_count finite numbers); another vehicle (vehicle
// checksum) or another arm_count than arm_count; a value out of range
// (|o_i| above max_offset_rad, tare.max_offset_rad; a sigma outside
// vehicle.gauge_offset_std_rad's [1e-9, 1e-2] rad; r outside [0.4, 2] (the
// tip-mass map's) or its sigma outside [1e-6, 1]).
bool ReadVehicleGaugeState(const std::string& path, const std::string& vehicle_checksum, int arm_count,
                           double max_offset_rad, const MessageAuthenticator& authenticator, MultiArmGaugeState* state,
                           std::string* error);

}  // namespace birotor
