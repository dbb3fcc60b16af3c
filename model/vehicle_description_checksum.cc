#include "model/vehicle_description_checksum.h"

#include <algorithm>
#include <charconv>
#include <string>

#include "numerics/fnv1a.h"

namespace birotor {
namespace {

// Bump when the canonical text changes (field added, renamed, reordered).
constexpr const char* kCanonicalTextVersion = "vehicle_description_checksum: 1\n";

void AddLine(const std::string& key, const std::string& value, std::string* text) {
  *text += key;
  *text += ": ";
  *text += value;
  *text += '\n';
}

void AddReal(const std::string& key, double value, std::string* text) {
  char digits[32];
  const std::to_chars_result result = std::to_chars(digits, digits + sizeof(digits), value);
  AddLine(key, std::string(digits, result.ptr), text);
}

void AddArm(const std::string& stem, const ArmDescription& arm, std::string* text) {
  AddReal(stem + "angle_rad", arm.angle_rad, text);
  AddReal(stem + "length_m", arm.length_m, text);
  AddReal(stem + "thrust_angle_rad", arm.thrust_angle_rad, text);
  AddLine(stem + "spin", std::to_string(arm.spin), text);
  AddReal(stem + "stiffness_n_m_rad", arm.stiffness_n_m_rad, text);
  AddReal(stem + "damping_n_m_s_rad", arm.damping_n_m_s_rad, text);
  AddReal(stem + "tip_mass_kg", arm.tip_mass_kg, text);
  AddReal(stem + "thrust_coeff_n_s2_rad2", arm.thrust_coeff_n_s2_rad2, text);
  AddReal(stem + "motor_time_constant_s", arm.motor_time_constant_s, text);
  AddLine(stem + "has_gauge", arm.has_gauge ? "true" : "false", text);
  AddReal(stem + "gauge_scale", arm.gauge_scale, text);
  AddReal(stem + "gauge_offset_rad", arm.gauge_offset_rad, text);
}

}  // namespace

std::string DescriptionCanonicalText(const VehicleDescription& d) {
  std::string text = kCanonicalTextVersion;
  AddLine("name", d.name, &text);
  AddLine("arm_count", std::to_string(d.arm_count), &text);
  AddReal("body_mass_kg", d.body_mass_kg, &text);
  AddReal("body_inertia_kg_m2", d.body_inertia_kg_m2, &text);
  AddReal("gravity_m_s2", d.gravity_m_s2, &text);
  AddReal("omega_max_rad_s", d.omega_max_rad_s, &text);
  AddReal("turbulence_std", d.turbulence_std, &text);
  AddReal("turbulence_corr_time_s", d.turbulence_corr_time_s, &text);
  AddReal("gauge_offset_std_rad", d.gauge_offset_std_rad, &text);
  AddReal("gauge_drift_psd_rad2_s", d.gauge_drift_psd_rad2_s, &text);
  const int arms = std::clamp(d.arm_count, 0, kMaxArms);
  for (int i = 0; i < arms; ++i) {
    AddArm("arms[" + std::to_string(i) + "].", d.arms[static_cast<size_t>(i)], &text);
  }
  return text;
}

std::string DescriptionChecksum(const VehicleDescription& description) {
  return TextChecksumHex(DescriptionCanonicalText(description));
}

}  // namespace birotor
