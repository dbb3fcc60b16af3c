#include "params/birotor_params_yaml.h"

#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "model/vehicle_description.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {

const std::vector<VehicleKey>& VehicleKeys() {
  static const std::vector<VehicleKey> keys = {
      {"body_mass_kg", 1e-3, 1e3, &BirotorParams::body_mass_kg},
      {"tip_mass_kg", 1e-4, 1e2, &BirotorParams::tip_mass_kg},
      {"arm_length_m", 1e-3, 10.0, &BirotorParams::arm_length_m},
      {"body_inertia_kg_m2", 1e-6, 1e3, &BirotorParams::body_inertia_kg_m2},
      {"arm_stiffness_n_m_rad", 1e-3, 1e7, &BirotorParams::arm_stiffness_n_m_rad},
      {"arm_damping_n_m_s_rad", 0.0, 1e4, &BirotorParams::arm_damping_n_m_s_rad},
      {"gravity_m_s2", 0.0, 100.0, &BirotorParams::gravity_m_s2},
      {"thrust_coeff_n_s2_rad2", 1e-9, 1.0, &BirotorParams::thrust_coeff_n_s2_rad2},
      {"motor_time_constant_s", 1e-4, 10.0, &BirotorParams::motor_time_constant_s},
      {"omega_max_rad_s", 1.0, 1e5, &BirotorParams::omega_max_rad_s},
      {"turbulence_std", 0.0, 1.0, &BirotorParams::turbulence_std},
      {"turbulence_corr_time_s", 1e-4, 100.0, &BirotorParams::turbulence_corr_time_s},
      {"gauge_offset_std_rad", 1e-9, 1e-2, &BirotorParams::gauge_offset_std_rad},
      {"gauge_drift_psd_rad2_s", 0.0, 1e-6, &BirotorParams::gauge_drift_psd_rad2_s},
  };
  return keys;
}

const VehicleKey& FindVehicleKey(const std::string& name) {
  for (const VehicleKey& key : VehicleKeys()) {
    if (name == key.name) return key;
  }
  throw std::logic_error("FindVehicleKey: no vehicle key " + name);
}

void ReadBirotorParams(YamlSection s, BirotorParams* p) {
  for (const VehicleKey& key : VehicleKeys()) s.Double(key.name, key.min, key.max, &(p->*key.field));
  s.DoubleArray("gauge_scale", 2, kGaugeScaleMin, kGaugeScaleMax, p->gauge_scale);
  s.DoubleArray("gauge_offset_rad", 2, -kGaugeOffsetMaxRad, kGaugeOffsetMaxRad, p->gauge_offset_rad);
  s.Finish();
  if (!s.HasMissingKeys()) CheckPlausible(s, BirotorDescription(*p));
}

BirotorParams LoadBirotorParams(const std::string& file) {
  BirotorParams params;
  WithFileErrors(file, [&] {
    YamlSection root = YamlSection::LoadFile(file);
    ReadBirotorParams(root.Section("vehicle"), &params);
    root.CheckComplete();
  });
  return params;
}

std::string BirotorParamsYaml(const BirotorParams& p, const std::string& indent) {
  return BirotorParamsYaml(p, {}, indent);
}

std::string BirotorParamsYaml(const BirotorParams& p, const std::vector<std::pair<std::string, std::string>>& comments,
                              const std::string& indent) {
  std::ostringstream out;
  out << std::setprecision(10);
  out << "vehicle:\n";
  for (const VehicleKey& key : VehicleKeys()) {
    out << indent << key.name << ": " << p.*key.field;
    for (const auto& [name, comment] : comments) {
      if (name == key.name) out << "  # " << comment;
    }
    out << "\n";
  }
  out << indent << "gauge_scale: [" << p.gauge_scale[0] << ", " << p.gauge_scale[1] << "]\n";
  out << indent << "gauge_offset_rad: [" << p.gauge_offset_rad[0] << ", " << p.gauge_offset_rad[1] << "]\n";
  return out.str();
}

}  // namespace birotor
