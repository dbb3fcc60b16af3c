#include "params/vehicle_description_yaml.h"

#include <vector>

#include "params/birotor_params_yaml.h"
#include "params/option_table.h"

namespace birotor {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A row of the N-arm tables with the range of the birotor key it matches, so
// that a value allowed in one form is allowed in the other.
template <typename Struct>
OptionKey<Struct> RealLike(const char* name, double Struct::*field, const std::string& birotor_key) {
  const VehicleKey& key = FindVehicleKey(birotor_key);
  return Real(name, field, key.min, key.max);
}

// The body keys of the N-arm form (defaults: VehicleDescription).
const OptionTable<VehicleDescription>& BodyKeys() {
  using V = VehicleDescription;
  static const OptionTable<V> keys = {
      Text("name", &V::name),
      RealLike("body_mass_kg", &V::body_mass_kg, "body_mass_kg"),
      RealLike("body_inertia_kg_m2", &V::body_inertia_kg_m2, "body_inertia_kg_m2"),
      RealLike("gravity_m_s2", &V::gravity_m_s2, "gravity_m_s2"),
      RealLike("omega_max_rad_s", &V::omega_max_rad_s, "omega_max_rad_s"),
      RealLike("turbulence_std", &V::turbulence_std, "turbulence_std"),
      RealLike("turbulence_corr_time_s", &V::turbulence_corr_time_s, "turbulence_corr_time_s"),
      RealLike("gauge_offset_std_rad", &V::gauge_offset_std_rad, "gauge_offset_std_rad"),
      RealLike("gauge_drift_psd_rad2_s", &V::gauge_drift_psd_rad2_s, "gauge_drift_psd_rad2_s"),
  };
  return keys;
}

// The keys of each element of `arms:` but its two angles (ReadAngle).
const OptionTable<ArmDescription>& ArmKeys() {
  using A = ArmDescription;
  static const OptionTable<A> keys = {
      RealLike("length_m", &A::length_m, "arm_length_m"),
      Integer("spin", &A::spin, -1, 1),  // and not 0
      RealLike("stiffness_n_m_rad", &A::stiffness_n_m_rad, "arm_stiffness_n_m_rad"),
      RealLike("damping_n_m_s_rad", &A::damping_n_m_s_rad, "arm_damping_n_m_s_rad"),
      RealLike("tip_mass_kg", &A::tip_mass_kg, "tip_mass_kg"),
      RealLike("thrust_coeff_n_s2_rad2", &A::thrust_coeff_n_s2_rad2, "thrust_coeff_n_s2_rad2"),
      RealLike("motor_time_constant_s", &A::motor_time_constant_s, "motor_time_constant_s"),
      Flag("has_gauge", &A::has_gauge),
      Real("gauge_scale", &A::gauge_scale, kGaugeScaleMin, kGaugeScaleMax),
      Real("gauge_offset_rad", &A::gauge_offset_rad, -kGaugeOffsetMaxRad, kGaugeOffsetMaxRad),
  };
  return keys;
}

// The keys only the birotor form has: with `arms:` they make a file of both forms.
std::vector<std::string> BirotorOnlyKeys() {
  std::vector<std::string> keys = {"gauge_scale", "gauge_offset_rad"};
  for (const VehicleKey& key : VehicleKeys()) {
    bool body = false;
    for (const OptionKey<VehicleDescription>& row : BodyKeys()) body = body || (row.name == std::string(key.name));
    if (!body) keys.push_back(key.name);
  }
  return keys;
}

// alpha or theta: `<stem>_rad` in [-2 pi, 2 pi], or as a convenience
// `<stem>_deg` in [-360, 360] (converted deg pi / 180); exactly one of them.
void ReadAngle(YamlSection& arm, const std::string& stem, double* angle_rad) {
  const std::string rad_key = stem + "_rad", deg_key = stem + "_deg";
  if (arm.Has(rad_key) && arm.Has(deg_key)) {
    arm.Fail(deg_key, "given with " + rad_key + "; give one of them",
             rad_key + " in " + RangeText(-2.0 * kPi, 2.0 * kPi) + " or " + deg_key + " in [-360, 360]");
  }
  if (!arm.Has(deg_key)) {
    arm.Double(rad_key, -2.0 * kPi, 2.0 * kPi, angle_rad);
    return;
  }
  double angle_deg = 0.0;
  arm.Double(deg_key, -360.0, 360.0, &angle_deg);
  *angle_rad = angle_deg * kPi / 180.0;
}

void ReadArm(YamlSection arm, ArmDescription* out) {
  ReadAngle(arm, "angle", &out->angle_rad);
  ReadAngle(arm, "thrust_angle", &out->thrust_angle_rad);
  ReadOptions(arm, ArmKeys(), out);
  if (out->spin == 0) arm.Fail("spin", "value 0: a rotor turns one way or the other", "1 or -1");
  arm.Finish();
}

// The N-arm form: body keys, then each arm.
void ReadArmsForm(YamlSection& s, VehicleDescription* d) {
  ReadOptions(s, BodyKeys(), d);
  std::vector<YamlSection> arms = s.SectionList("arms");
  const int count = static_cast<int>(arms.size());
  if (s.Has("arms") && (count < kBirotorArmCount || count > kMaxArms)) {
    s.Fail("arms", "a list of " + std::to_string(count) + " arms",
           "[" + std::to_string(kBirotorArmCount) + ", " + std::to_string(kMaxArms) + "] arms, each a map");
  }
  d->arm_count = count;
  for (int i = 0; i < count; ++i) ReadArm(arms[static_cast<size_t>(i)], &d->arms[static_cast<size_t>(i)]);
  s.Finish();
}

}  // namespace

void ReadVehicleDescription(YamlSection s, VehicleDescription* d) {
  std::string birotor_keys;
  for (const std::string& key : BirotorOnlyKeys()) {
    if (s.Has(key)) birotor_keys += (birotor_keys.empty() ? "" : ", ") + s.KeyPath(key);
  }
  if (s.Has("arms") && !birotor_keys.empty()) {
    throw ParamError(s.file() + ": key " + Quoted(s.path()) + ": holds both the N-arm form (" + s.KeyPath("arms") +
                     ") and the birotor form (" + birotor_keys +
                     "): give one of them (docs/vehicle-description.md, \"File format\")");
  }
  if (!birotor_keys.empty()) {
    BirotorParams params;
    ReadBirotorParams(s, &params);  // and CheckPlausible
    *d = BirotorDescription(params);
    return;
  }
  ReadArmsForm(s, d);
  if (!s.HasMissingKeys()) CheckPlausible(s, *d);
}

void RequireBirotor(const std::string& file, const std::string& who, const VehicleDescription& d) {
  BirotorParams params;
  std::string why;
  if (!ToBirotorParams(d, &params, &why)) {
    throw ParamError(file + ": key 'vehicle': " + who +
                     " runs the birotor's model and this vehicle is not a birotor: " + why +
                     " (docs/vehicle-description.md, \"Which programs take which vehicle\")");
  }
}

VehicleDescription LoadVehicleDescription(const std::string& file) {
  VehicleDescription description;
  WithFileErrors(file, [&] {
    YamlSection root = YamlSection::LoadFile(file);
    ReadVehicleDescription(root.Section("vehicle"), &description);
    root.CheckComplete();
  });
  return description;
}

VehicleDescription ParseVehicleDescription(const std::string& text, const std::string& file) {
  VehicleDescription description;
  WithFileErrors(file, [&] {
    YamlSection root = YamlSection::LoadString(text, file);
    ReadVehicleDescription(root.Section("vehicle"), &description);
    root.CheckComplete();
  });
  return description;
}

bool IsArmsForm(const std::string& text) {
  try {
    YamlSection root = YamlSection::LoadString(text, "");
    return root.Has("vehicle") && root.Section("vehicle").Has("arms");
  } catch (const std::exception&) {
    return false;
  }
}

void CheckPlausible(const YamlSection& section, const VehicleDescription& description) {
  const std::vector<std::string> problems = PlausibilityProblems(description);
  if (problems.empty()) return;
  std::string text;
  for (const std::string& problem : problems) text += (text.empty() ? "" : "; ") + problem;
  throw ParamError(section.file() + ": key " + Quoted(section.path()) + ": the vehicle cannot fly: " + text +
                   " (docs/vehicle-description.md, \"Plausibility\")");
}

}  // namespace birotor
