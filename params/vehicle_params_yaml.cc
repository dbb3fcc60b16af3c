#include "params/vehicle_params_yaml.h"

#include <iomanip>
#include <sstream>

namespace birotor {

void ReadVehicleParams(YamlSection s, VehicleParams* p) {
  s.Double("body_mass_kg", 1e-3, 1e3, &p->body_mass_kg);
  s.Double("tip_mass_kg", 1e-4, 1e2, &p->tip_mass_kg);
  s.Double("arm_length_m", 1e-3, 10.0, &p->arm_length_m);
  s.Double("body_inertia_kg_m2", 1e-6, 1e3, &p->body_inertia_kg_m2);
  s.Double("arm_stiffness_n_m_rad", 1e-3, 1e7, &p->arm_stiffness_n_m_rad);
  s.Double("arm_damping_n_m_s_rad", 0.0, 1e4, &p->arm_damping_n_m_s_rad);
  s.Double("gravity_m_s2", 0.0, 100.0, &p->gravity_m_s2);
  s.Double("thrust_coeff_n_s2_rad2", 1e-9, 1.0, &p->thrust_coeff_n_s2_rad2);
  s.Double("motor_time_constant_s", 1e-4, 10.0, &p->motor_time_constant_s);
  s.Double("omega_max_rad_s", 1.0, 1e5, &p->omega_max_rad_s);
  s.Double("turbulence_std", 0.0, 1.0, &p->turbulence_std);
  s.Double("turbulence_corr_time_s", 1e-4, 100.0, &p->turbulence_corr_time_s);
  s.DoubleArray("gauge_scale", 2, 0.5, 2.0, p->gauge_scale);
  s.DoubleArray("gauge_offset_rad", 2, -1e-2, 1e-2, p->gauge_offset_rad);
  s.Double("gauge_offset_std_rad", 1e-9, 1e-2, &p->gauge_offset_std_rad);
  s.Double("gauge_drift_psd_rad2_s", 0.0, 1e-6, &p->gauge_drift_psd_rad2_s);
  s.Finish();
}

VehicleParams LoadVehicleParams(const std::string& file) {
  YamlSection root = YamlSection::LoadFile(file);
  if (!root.Has("vehicle")) root.Fail("vehicle", "missing", "a mapping with the vehicle parameters");
  VehicleParams params;
  ReadVehicleParams(root.Section("vehicle"), &params);
  return params;
}

std::string VehicleParamsYaml(const VehicleParams& p, const std::string& indent) {
  std::ostringstream out;
  out << std::setprecision(10);
  out << "vehicle:\n";
  out << indent << "body_mass_kg: " << p.body_mass_kg << "\n";
  out << indent << "tip_mass_kg: " << p.tip_mass_kg << "\n";
  out << indent << "arm_length_m: " << p.arm_length_m << "\n";
  out << indent << "body_inertia_kg_m2: " << p.body_inertia_kg_m2 << "\n";
  out << indent << "arm_stiffness_n_m_rad: " << p.arm_stiffness_n_m_rad << "\n";
  out << indent << "arm_damping_n_m_s_rad: " << p.arm_damping_n_m_s_rad << "\n";
  out << indent << "gravity_m_s2: " << p.gravity_m_s2 << "\n";
  out << indent << "thrust_coeff_n_s2_rad2: " << p.thrust_coeff_n_s2_rad2 << "\n";
  out << indent << "motor_time_constant_s: " << p.motor_time_constant_s << "\n";
  out << indent << "omega_max_rad_s: " << p.omega_max_rad_s << "\n";
  out << indent << "turbulence_std: " << p.turbulence_std << "\n";
  out << indent << "turbulence_corr_time_s: " << p.turbulence_corr_time_s << "\n";
  out << indent << "gauge_scale: [" << p.gauge_scale[0] << ", " << p.gauge_scale[1] << "]\n";
  out << indent << "gauge_offset_rad: [" << p.gauge_offset_rad[0] << ", " << p.gauge_offset_rad[1] << "]\n";
  out << indent << "gauge_offset_std_rad: " << p.gauge_offset_std_rad << "\n";
  out << indent << "gauge_drift_psd_rad2_s: " << p.gauge_drift_psd_rad2_s << "\n";
  return out.str();
}

}  // namespace birotor
