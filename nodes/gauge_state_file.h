// The persisted strain-gauge offsets: at a clean stop birotor-estimator writes
// the offsets it learned (tare or filter) to a small text file, and starts
// from them after a restart, so that a restart in the air is not an untared
// start. The file names the vehicle it belongs to (a checksum of every key of
// the vehicle section) and carries a checksum of its own lines: a corrupt or
// foreign file is refused with a one-line reason. The daemon writes and reads
// it authenticated under the site key (issue 37 item 4): a forged file, even
// with a right checksum and in-range values, is refused.
#pragma once

#include <string>

#include "estimator/estimator_pipeline.h"
#include "estimator/gauge_calibration.h"
#include "model/birotor_params.h"
#include "security/message_authenticator.h"

namespace birotor {

// Checksum of the vehicle parameters (BirotorParamsYaml text, FNV-1a 64).
std::string VehicleChecksum(const BirotorParams& params);

// The state file's range check of a learned tip mass (m_p in the range of
// vehicle.tip_mass_kg, [1e-4, 100] kg; its sigma in [1e-6, 1] kg): "" when
// both are within, else the reason ("tip_mass_kg 150 outside [0.0001, 100]
// kg (the range of vehicle.tip_mass_kg)"). For a tip mass read elsewhere (a
// flight log's ESTIMATOR_LEARNED_N, nodes/recorded_tip_mass.h).
std::string LearnedTipMassRangeProblem(double tip_mass_kg, double std_kg);

// File text for the offsets and std of calibration.
//   # birotor-estimator gauge offset state
//   vehicle_checksum: <16 hex>
//   gauge_offset_rad: <o1> <o2>
//   gauge_offset_std_rad: <s1> <s2>
//   strain_scale: <g1> <g2>            (only when learned, EkfOptions::learn_strain_scale)
//   strain_scale_std: <s1> <s2>        (its one sigma)
//   tip_mass_kg: <m>                   (only when learned, model_consistency arm_mode_learn_tip_mass)
//   tip_mass_std_kg: <s>               (its one sigma)
//   checksum: <16 hex of the lines above>
std::string GaugeStateText(const GaugeCalibration& calibration, const std::string& vehicle_checksum);

// What the daemon persists at a clean stop: the calibration in use (offsets;
// the offset-departure test's anchor instead when they departed;
// learned strain scales) and the tip mass the arm-mode test learned, if it did.
GaugeCalibration PersistedGaugeState(const PipelineHealth& health);

// Writes the text to path through a uniquely named temporary file in the same
// folder (O_CREAT | O_EXCL | O_NOFOLLOW) and a rename: a reader sees the old or
// the new file, and a pre-planted link is never written through. Refused
// (false, *error, nothing written) when path exists and is not a gauge state
// file (a link, a FIFO, a device, or a regular file without the header line:
// the parameter file given as state_file survives), or when an offset or its
// std is not finite. A std outside the reader's range is written at its bound;
// a learned strain scale or tip mass outside it is left out. An existing state file keeps its mode and owner; a new one
// is 0644.
bool WriteGaugeState(const std::string& path, const GaugeCalibration& calibration, const std::string& vehicle_checksum,
                     std::string* error);

// Reads offsets and std into *calibration (source kStateFile). False with a
// one-line *error, *calibration unchanged, for: a path that is not a regular
// file (a symbolic link, a FIFO: refused without waiting, a device such as
// /dev/zero: refused before a byte is read) or larger than 4 kB; a corrupt file
// (bad checksum, bad or missing field; strain_scale and strain_scale_std
// are optional, together, g_i in [0.2, 5] and its sigma in [1e-6, 0.5]:
// has_strain_scale says whether they were there; so are tip_mass_kg and
// tip_mass_std_kg, m_p in vehicle.tip_mass_kg's range [1e-4, 100] kg and its
// sigma in [1e-6, 1] kg: has_tip_mass); a value out of range (|o_i| above
// max_offset_rad, a std outside the range of vehicle.gauge_offset_std_rad,
// [1e-9, 1e-2] rad: the checksum does not stop a forged file); or a foreign
// file (other vehicle checksum).
// A trailing mac line (the authenticated file below) is not checked here:
// this reader only says what a file is (birotor-identify --learned deploys
// nothing from it: it reads with the site key, nodes/learned_values_file.h).
bool ReadGaugeState(const std::string& path, const std::string& vehicle_checksum, double max_offset_rad,
                    GaugeCalibration* calibration, std::string* error);

// The authenticated state file, what birotor-estimator writes and restores:
// the text above and one more line,
//   mac: <64 hex>   HMAC-SHA-512-256 under the site key (MessageAuthenticator,
//                   counter 0) of every byte before this line
// The file is rewritten at each stop, so its counter is fixed: an older
// genuine file of the same vehicle and key still verifies (no replay defence).
bool WriteGaugeState(const std::string& path, const GaugeCalibration& calibration, const std::string& vehicle_checksum,
                     const MessageAuthenticator& authenticator, std::string* error);

// ReadGaugeState, and before any field is looked at the mac line must be
// there and verify: else false, *error "<path>: not authenticated (...)",
// *calibration unchanged.
bool ReadGaugeState(const std::string& path, const std::string& vehicle_checksum, double max_offset_rad,
                    const MessageAuthenticator& authenticator, GaugeCalibration* calibration, std::string* error);

}  // namespace birotor
