#include "nodes/gauge_state_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "nodes/state_file_common.h"
#include "params/birotor_params_yaml.h"
#include "params/regular_file.h"
#include "program/logging.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {

constexpr const char* kHeader = kBirotorStateHeader;

using StdRange = StateValueRange;

// Two finite numbers from "a b"; false otherwise.
bool ParsePair(const std::string& text, double out[2]) { return ParseFiniteNumbers(text, 2, out); }

// The learned strain scale g_i (optional lines, issue 27): the filter's
// numerical range, and a sigma between "known" and its widest prior.
constexpr StdRange kStrainScaleRange = {0.2, 5.0};
constexpr StdRange kStrainScaleStdRange = {1e-6, 0.5};

bool ReadStrainScale(const std::string& path, std::map<std::string, std::string>& fields, double scale[kBirotorRotors],
                     double scale_std[kBirotorRotors], std::string* error) {
  if (!ParsePair(fields["strain_scale"], scale) || !ParsePair(fields["strain_scale_std"], scale_std)) {
    *error = path + ": corrupt (strain_scale or strain_scale_std not two finite numbers)";
    return false;
  }
  for (int i = 0; i < 2; ++i) {
    if (!(scale[i] >= kStrainScaleRange.min && scale[i] <= kStrainScaleRange.max)) {
      *error = path + ": strain_scale " + fields["strain_scale"] + " outside " +
               RangeText(kStrainScaleRange.min, kStrainScaleRange.max) + ": refused";
      return false;
    }
    if (!(scale_std[i] >= kStrainScaleStdRange.min && scale_std[i] <= kStrainScaleStdRange.max)) {
      *error = path + ": strain_scale_std " + fields["strain_scale_std"] + " outside " +
               RangeText(kStrainScaleStdRange.min, kStrainScaleStdRange.max) + ": refused";
      return false;
    }
  }
  return true;
}

// The learned tip mass (optional lines, issue 36): the range of the vehicle
// key tip_mass_kg, and a sigma between "known" and a kilogram (the reference
// prior is 0.043 kg).
StdRange TipMassRange() { return VehicleKeyRange("tip_mass_kg"); }
constexpr StdRange kTipMassStdRange = {1e-6, 1.0};

// A finite number from "a"; false otherwise.
bool ParseNumber(const std::string& text, double* out) { return ParseFiniteNumbers(text, 1, out); }

// The range check of a learned tip mass, its text as written: "" or the reason.
std::string TipMassRangeProblem(double mass_kg, const std::string& mass_text, double std_kg,
                                const std::string& std_text) {
  const StdRange range = TipMassRange();
  if (!(mass_kg >= range.min && mass_kg <= range.max)) {
    return "tip_mass_kg " + mass_text + " outside " + RangeText(range.min, range.max) +
           " kg (the range of vehicle.tip_mass_kg)";
  }
  if (!(std_kg >= kTipMassStdRange.min && std_kg <= kTipMassStdRange.max)) {
    return "tip_mass_std_kg " + std_text + " outside " + RangeText(kTipMassStdRange.min, kTipMassStdRange.max) + " kg";
  }
  return "";
}

bool ReadTipMass(const std::string& path, std::map<std::string, std::string>& fields, double* mass_kg, double* std_kg,
                 std::string* error) {
  if (!ParseNumber(fields["tip_mass_kg"], mass_kg) || !ParseNumber(fields["tip_mass_std_kg"], std_kg)) {
    *error = path + ": corrupt (tip_mass_kg or tip_mass_std_kg not a finite number)";
    return false;
  }
  const std::string problem = TipMassRangeProblem(*mass_kg, fields["tip_mass_kg"], *std_kg, fields["tip_mass_std_kg"]);
  if (!problem.empty()) {
    *error = path + ": " + problem + ": refused";
    return false;
  }
  return true;
}

bool WriteStateText(const std::string& path, const GaugeCalibration& calibration, const std::string& vehicle_checksum,
                    const MessageAuthenticator* authenticator, std::string* error);
bool ParseStateText(const std::string& path, const std::string& text, const std::string& vehicle_checksum,
                    double max_offset_rad, GaugeCalibration* calibration, std::string* error);

}  // namespace

std::string VehicleChecksum(const BirotorParams& params) { return TextChecksum(BirotorParamsYaml(params)); }

std::string LearnedTipMassRangeProblem(double tip_mass_kg, double std_kg) {
  char mass_text[32], std_text[32];
  std::snprintf(mass_text, sizeof(mass_text), "%.10g", tip_mass_kg);
  std::snprintf(std_text, sizeof(std_text), "%.10g", std_kg);
  return TipMassRangeProblem(tip_mass_kg, mass_text, std_kg, std_text);
}

GaugeCalibration PersistedGaugeState(const PipelineHealth& health) {
  GaugeCalibration state = health.gauge;
  const OffsetDepartureState& offsets = health.consistency.offsets;
  if (offsets.departed) {
    // The offsets took a force (a payload): the next start keeps the anchor
    // they left, so that it sees the payload again instead of flying on it.
    for (int i = 0; i < kBirotorRotors; ++i) {
      state.offset_rad[i] = offsets.anchor_rad[i];
      state.offset_std_rad[i] = offsets.anchor_std_rad[i];
    }
  }
  state.has_tip_mass = health.tip_mass_learned;
  state.tip_mass_kg = health.tip_mass_kg;
  state.tip_mass_std_kg = health.tip_mass_std_kg;
  return state;
}

std::string GaugeStateText(const GaugeCalibration& calibration, const std::string& vehicle_checksum) {
  char body[512];
  int length = std::snprintf(
      body, sizeof(body), "%svehicle_checksum: %s\ngauge_offset_rad: %.17g %.17g\ngauge_offset_std_rad: %.17g %.17g\n",
      kHeader, vehicle_checksum.c_str(), calibration.offset_rad[0], calibration.offset_rad[1],
      calibration.offset_std_rad[0], calibration.offset_std_rad[1]);
  if (calibration.has_strain_scale && length > 0 && length < static_cast<int>(sizeof(body))) {
    length +=
        std::snprintf(body + length, sizeof(body) - length,
                      "strain_scale: %.17g %.17g\nstrain_scale_std: %.17g %.17g\n", calibration.strain_scale[0],
                      calibration.strain_scale[1], calibration.strain_scale_std[0], calibration.strain_scale_std[1]);
  }
  if (calibration.has_tip_mass && length > 0 && length < static_cast<int>(sizeof(body))) {
    std::snprintf(body + length, sizeof(body) - length, "tip_mass_kg: %.17g\ntip_mass_std_kg: %.17g\n",
                  calibration.tip_mass_kg, calibration.tip_mass_std_kg);
  }
  return std::string(body) + "checksum: " + TextChecksum(body) + "\n";
}

bool WriteGaugeState(const std::string& path, const GaugeCalibration& calibration, const std::string& vehicle_checksum,
                     std::string* error) {
  return WriteStateText(path, calibration, vehicle_checksum, nullptr, error);
}

bool WriteGaugeState(const std::string& path, const GaugeCalibration& calibration, const std::string& vehicle_checksum,
                     const MessageAuthenticator& authenticator, std::string* error) {
  return WriteStateText(path, calibration, vehicle_checksum, &authenticator, error);
}

bool ReadGaugeState(const std::string& path, const std::string& vehicle_checksum, double max_offset_rad,
                    GaugeCalibration* calibration, std::string* error) {
  std::string text;
  if (!ReadStateFileText(path, nullptr, &text, error)) return false;
  return ParseStateText(path, text, vehicle_checksum, max_offset_rad, calibration, error);
}

bool ReadGaugeState(const std::string& path, const std::string& vehicle_checksum, double max_offset_rad,
                    const MessageAuthenticator& authenticator, GaugeCalibration* calibration, std::string* error) {
  std::string text;
  if (!ReadStateFileText(path, &authenticator, &text, error)) return false;
  return ParseStateText(path, text, vehicle_checksum, max_offset_rad, calibration, error);
}

namespace {

bool WriteStateText(const std::string& path, const GaugeCalibration& calibration, const std::string& vehicle_checksum,
                    const MessageAuthenticator* authenticator, std::string* error) {
  FileAttributes attributes;
  if (!ReplaceableStateFile(path, kHeader, &attributes, error)) return false;
  GaugeCalibration written = calibration;
  const StdRange std_range = GaugeOffsetStdRange();
  for (int i = 0; i < 2; ++i) {
    if (!std::isfinite(calibration.offset_rad[i]) || !std::isfinite(calibration.offset_std_rad[i])) {
      *error = path + ": gauge offset " + std::to_string(calibration.offset_rad[i]) + " +- " +
               std::to_string(calibration.offset_std_rad[i]) + " rad is not finite: not written";
      return false;
    }
    // A std outside the reader's range is written at its bound (a learned
    // std below 1e-9 rad is floored: the file then claims less, never more).
    written.offset_std_rad[i] = std::min(std::max(calibration.offset_std_rad[i], std_range.min), std_range.max);
    // A learned strain scale outside the reader's range is not written (the
    // next start learns it again from the file's value).
    if (!(calibration.strain_scale[i] >= kStrainScaleRange.min &&
          calibration.strain_scale[i] <= kStrainScaleRange.max && std::isfinite(calibration.strain_scale_std[i]))) {
      written.has_strain_scale = false;
    }
    written.strain_scale_std[i] =
        std::min(std::max(calibration.strain_scale_std[i], kStrainScaleStdRange.min), kStrainScaleStdRange.max);
  }
  // The same for a learned tip mass: not written outside the reader's range,
  // its sigma written at the range's bound.
  const StdRange tip_range = TipMassRange();
  if (!(calibration.tip_mass_kg >= tip_range.min && calibration.tip_mass_kg <= tip_range.max &&
        std::isfinite(calibration.tip_mass_std_kg))) {
    written.has_tip_mass = false;
  }
  written.tip_mass_std_kg = std::min(std::max(calibration.tip_mass_std_kg, kTipMassStdRange.min), kTipMassStdRange.max);
  std::string text = GaugeStateText(written, vehicle_checksum);
  if (authenticator != nullptr) text += StateFileMacLine(text, *authenticator);
  return ReplaceRegularFile(path, text, attributes, error);
}

bool ParseStateText(const std::string& path, const std::string& text, const std::string& vehicle_checksum,
                    double max_offset_rad, GaugeCalibration* calibration, std::string* error) {
  std::map<std::string, std::string> fields;
  if (!ChecksummedStateFields(path, text, kHeader, &fields, error)) return false;
  if (fields["vehicle_checksum"] != vehicle_checksum) {
    *error = path + ": written for another vehicle or parameter file (vehicle checksum " + fields["vehicle_checksum"] +
             ", expected " + vehicle_checksum + ")";
    return false;
  }
  // The checksum is no defence against a forged file (anyone can recompute
  // it): every value is range-checked as the parameter file's would be.
  double offset[kBirotorRotors], std_rad[2];
  const StdRange std_range = GaugeOffsetStdRange();
  if (!ParsePair(fields["gauge_offset_rad"], offset) || !ParsePair(fields["gauge_offset_std_rad"], std_rad)) {
    *error = path + ": corrupt (gauge_offset_rad or gauge_offset_std_rad missing or not two finite numbers)";
    return false;
  }
  for (int i = 0; i < 2; ++i) {
    if (!(std::abs(offset[i]) <= max_offset_rad)) {
      *error = path + ": gauge_offset_rad " + fields["gauge_offset_rad"] + " outside [-" +
               std::to_string(max_offset_rad) + ", " + std::to_string(max_offset_rad) +
               "] rad (tare.max_offset_rad): refused";
      return false;
    }
    if (!(std_rad[i] >= std_range.min && std_rad[i] <= std_range.max)) {
      *error = path + ": gauge_offset_std_rad " + fields["gauge_offset_std_rad"] + " outside " +
               RangeText(std_range.min, std_range.max) + " rad (the range of vehicle.gauge_offset_std_rad): refused";
      return false;
    }
  }
  double scale[kBirotorRotors] = {1.0, 1.0}, scale_std[kBirotorRotors] = {0.0, 0.0};
  const bool has_scale = fields.count("strain_scale") > 0 || fields.count("strain_scale_std") > 0;
  if (has_scale && !ReadStrainScale(path, fields, scale, scale_std, error)) return false;
  double tip_mass_kg = 0, tip_mass_std_kg = 0;
  const bool has_tip_mass = fields.count("tip_mass_kg") > 0 || fields.count("tip_mass_std_kg") > 0;
  if (has_tip_mass && !ReadTipMass(path, fields, &tip_mass_kg, &tip_mass_std_kg, error)) return false;
  for (int i = 0; i < 2; ++i) {
    calibration->offset_rad[i] = offset[i];
    calibration->offset_std_rad[i] = std_rad[i];
    calibration->strain_scale[i] = scale[i];
    calibration->strain_scale_std[i] = scale_std[i];
  }
  calibration->has_strain_scale = has_scale;
  calibration->has_tip_mass = has_tip_mass;
  calibration->tip_mass_kg = tip_mass_kg;
  calibration->tip_mass_std_kg = tip_mass_std_kg;
  calibration->source = GaugeOffsetSource::kStateFile;
  return true;
}

}  // namespace
}  // namespace birotor
