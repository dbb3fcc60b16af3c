#include "nodes/vehicle_state_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "estimator/tip_mass_learning.h"
#include "model/vehicle_description_checksum.h"
#include "nodes/state_file_common.h"
#include "params/regular_file.h"
#include "params/yaml_reader.h"
#include "program/logging.h"

namespace birotor {
namespace {

// The learned ratio r: the tip-mass map's range (what the learner can
// hold), and a sigma between "known" and 100 % (the prior's is 15 %).
constexpr StateValueRange kTipMassRatioRange = {ArmModeTipMassMap::kLowestRatio, ArmModeTipMassMap::kHighestRatio};
constexpr StateValueRange kTipMassRatioStdRange = {1e-6, 1.0};

bool Within(double value, const StateValueRange& range) { return value >= range.min && value <= range.max; }

double Clamped(double value, const StateValueRange& range) { return std::min(std::max(value, range.min), range.max); }

// " v_1 ... v_n" in the shortest text that reads back to the same doubles.
std::string NumbersText(const ArmValues& values, int n) {
  std::string text;
  char number[32];
  for (int i = 0; i < n; ++i) {
    std::snprintf(number, sizeof(number), " %.17g", values[static_cast<size_t>(i)]);
    text += number;
  }
  return text;
}

// Exactly n finite numbers from text; false otherwise.
bool ParseNumbers(const std::string& text, int n, ArmValues* out) { return ParseFiniteNumbers(text, n, out->data()); }

bool ParseNumber(const std::string& text, double* out) { return ParseFiniteNumbers(text, 1, out); }

// The per-arm lines: arm_count numbers each, every one in range.
bool ReadOffsets(const std::string& path, std::map<std::string, std::string>& fields, int arm_count,
                 double max_offset_rad, MultiArmGaugeState* state, std::string* error) {
  if (!ParseNumbers(fields["gauge_offset_rad"], arm_count, &state->offset_rad) ||
      !ParseNumbers(fields["gauge_offset_std_rad"], arm_count, &state->offset_std_rad)) {
    *error = path + ": corrupt (gauge_offset_rad or gauge_offset_std_rad missing or not " + std::to_string(arm_count) +
             " finite numbers)";
    return false;
  }
  const StateValueRange std_range = GaugeOffsetStdRange();
  for (int i = 0; i < arm_count; ++i) {
    const size_t k = static_cast<size_t>(i);
    if (!(std::abs(state->offset_rad[k]) <= max_offset_rad)) {
      *error = path + ": gauge_offset_rad " + fields["gauge_offset_rad"] + " outside " +
               RangeText(-max_offset_rad, max_offset_rad) + " rad (tare.max_offset_rad): refused";
      return false;
    }
    if (!Within(state->offset_std_rad[k], std_range)) {
      *error = path + ": gauge_offset_std_rad " + fields["gauge_offset_std_rad"] + " outside " +
               RangeText(std_range.min, std_range.max) + " rad (the range of vehicle.gauge_offset_std_rad): refused";
      return false;
    }
  }
  return true;
}

// The optional tip-mass lines: both or neither, each in range.
bool ReadTipMassRatio(const std::string& path, std::map<std::string, std::string>& fields, MultiArmGaugeState* state,
                      std::string* error) {
  state->has_tip_mass = fields.count("tip_mass_ratio") > 0 || fields.count("tip_mass_ratio_std") > 0;
  if (!state->has_tip_mass) return true;
  if (!ParseNumber(fields["tip_mass_ratio"], &state->tip_mass_ratio) ||
      !ParseNumber(fields["tip_mass_ratio_std"], &state->tip_mass_ratio_std)) {
    *error = path + ": corrupt (tip_mass_ratio or tip_mass_ratio_std not a finite number)";
    return false;
  }
  if (!Within(state->tip_mass_ratio, kTipMassRatioRange)) {
    *error = path + ": tip_mass_ratio " + fields["tip_mass_ratio"] + " outside " +
             RangeText(kTipMassRatioRange.min, kTipMassRatioRange.max) + " (the tip-mass map's): refused";
    return false;
  }
  if (!Within(state->tip_mass_ratio_std, kTipMassRatioStdRange)) {
    *error = path + ": tip_mass_ratio_std " + fields["tip_mass_ratio_std"] + " outside " +
             RangeText(kTipMassRatioStdRange.min, kTipMassRatioStdRange.max) + ": refused";
    return false;
  }
  return true;
}

// The vehicle and its arm count, before any value is looked at.
bool SameVehicle(const std::string& path, std::map<std::string, std::string>& fields,
                 const std::string& vehicle_checksum, int arm_count, std::string* error) {
  if (fields["vehicle_checksum"] != vehicle_checksum) {
    *error = path + ": written for another vehicle description (vehicle checksum " + fields["vehicle_checksum"] +
             ", expected " + vehicle_checksum + ")";
    return false;
  }
  if (fields["arm_count"] != std::to_string(arm_count)) {
    *error = path + ": arm_count " + fields["arm_count"] + ", the description has " + std::to_string(arm_count) +
             ": refused";
    return false;
  }
  return true;
}

}  // namespace

std::string VehicleStateChecksum(const VehicleDescription& vehicle) { return DescriptionChecksum(vehicle); }

std::string VehicleStateText(const MultiArmGaugeState& state, const std::string& vehicle_checksum) {
  std::string body = std::string(kVehicleStateHeader) + "vehicle_checksum: " + vehicle_checksum + "\n" +
                     "arm_count: " + std::to_string(state.arm_count) + "\n" +
                     "gauge_offset_rad:" + NumbersText(state.offset_rad, state.arm_count) + "\n" +
                     "gauge_offset_std_rad:" + NumbersText(state.offset_std_rad, state.arm_count) + "\n";
  if (state.has_tip_mass) {
    char lines[96];
    std::snprintf(lines, sizeof(lines), "tip_mass_ratio: %.17g\ntip_mass_ratio_std: %.17g\n", state.tip_mass_ratio,
                  state.tip_mass_ratio_std);
    body += lines;
  }
  return body + "checksum: " + TextChecksum(body) + "\n";
}

bool WriteVehicleGaugeState(const std::string& path, const MultiArmGaugeState& state,
                            const std::string& vehicle_checksum, const MessageAuthenticator& authenticator,
                            std::string* error) {
  FileAttributes attributes;
  if (!ReplaceableStateFile(path, kVehicleStateHeader, &attributes, error)) return false;
  MultiArmGaugeState written = state;
  const StateValueRange std_range = GaugeOffsetStdRange();
  for (int i = 0; i < state.arm_count; ++i) {
    const size_t k = static_cast<size_t>(i);
    if (!std::isfinite(state.offset_rad[k]) || !std::isfinite(state.offset_std_rad[k])) {
      *error = path + ": gauge offset " + std::to_string(state.offset_rad[k]) + " +- " +
               std::to_string(state.offset_std_rad[k]) + " rad of arm " + std::to_string(i + 1) +
               " is not finite: not written";
      return false;
    }
    // Floored or capped at the reader's range: the file then claims less, never more.
    written.offset_std_rad[k] = Clamped(state.offset_std_rad[k], std_range);
  }
  // A learned ratio outside the reader's range is not written (the next
  // start learns it again from the description's); its sigma at the bound.
  written.has_tip_mass =
      state.has_tip_mass && Within(state.tip_mass_ratio, kTipMassRatioRange) && std::isfinite(state.tip_mass_ratio_std);
  written.tip_mass_ratio_std = Clamped(state.tip_mass_ratio_std, kTipMassRatioStdRange);
  std::string text = VehicleStateText(written, vehicle_checksum);
  text += StateFileMacLine(text, authenticator);
  return ReplaceRegularFile(path, text, attributes, error);
}

bool ReadVehicleGaugeState(const std::string& path, const std::string& vehicle_checksum, int arm_count,
                           double max_offset_rad, const MessageAuthenticator& authenticator, MultiArmGaugeState* state,
                           std::string* error) {
  std::string text;
  std::map<std::string, std::string> fields;
  if (!ReadStateFileText(path, &authenticator, &text, error) ||
      !ChecksummedStateFields(path, text, kVehicleStateHeader, &fields, error) ||
      !SameVehicle(path, fields, vehicle_checksum, arm_count, error)) {
    return false;
  }
  // The checksum and the mac say who wrote it, not that its values are
  // sane: every value is range-checked as the description's would be.
  MultiArmGaugeState read;
  read.arm_count = arm_count;
  read.source = GaugeOffsetSource::kStateFile;
  if (!ReadOffsets(path, fields, arm_count, max_offset_rad, &read, error) ||
      !ReadTipMassRatio(path, fields, &read, error)) {
    return false;
  }
  *state = read;
  return true;
}

}  // namespace birotor
