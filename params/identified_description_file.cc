#include "params/identified_description_file.h"

#include <iomanip>
#include <limits>
#include <sstream>

namespace birotor {
namespace {

constexpr int kFullPrecision = std::numeric_limits<double>::max_digits10;

// "    key: value" and, for a fitted key, its sigma or the not-determined mark.
void WriteKey(std::ostringstream& out, const char* key, double value, const ParameterEstimate* estimate) {
  out << "      " << key << ": " << std::setprecision(kFullPrecision) << value;
  if (estimate != nullptr) {
    if (estimate->determined) {
      out << "  # +- " << std::setprecision(3) << estimate->sigma;
    } else {
      out << "  # NOT DETERMINED by these logs: value of the base file";
    }
  }
  out << "\n";
}

void WriteArm(std::ostringstream& out, const ArmDescription& a, const ArmEstimates* e) {
  out << "    - angle_rad: " << std::setprecision(kFullPrecision) << a.angle_rad << "\n";
  WriteKey(out, "thrust_angle_rad", a.thrust_angle_rad, nullptr);
  WriteKey(out, "length_m", a.length_m, nullptr);
  out << "      spin: " << a.spin << "\n";
  WriteKey(out, "stiffness_n_m_rad", a.stiffness_n_m_rad, e ? &e->stiffness : nullptr);
  WriteKey(out, "damping_n_m_s_rad", a.damping_n_m_s_rad, e ? &e->damping : nullptr);
  WriteKey(out, "tip_mass_kg", a.tip_mass_kg, e ? &e->tip_mass : nullptr);
  WriteKey(out, "thrust_coeff_n_s2_rad2", a.thrust_coeff_n_s2_rad2, e ? &e->thrust_coeff : nullptr);
  WriteKey(out, "motor_time_constant_s", a.motor_time_constant_s, e ? &e->motor_time_constant : nullptr);
  out << "      has_gauge: " << (a.has_gauge ? "true" : "false") << "\n";
  out << "      gauge_scale: " << std::setprecision(kFullPrecision) << a.gauge_scale
      << "  # held: the factory fact (shared/spec/gauges.md)\n";
  WriteKey(out, "gauge_offset_rad", a.gauge_offset_rad, e ? &e->gauge_offset : nullptr);
}

}  // namespace

std::string IdentifiedDescriptionYaml(const MultiArmIdentificationResult& result,
                                      const std::vector<std::string>& sources) {
  const VehicleDescription& v = result.vehicle;
  std::ostringstream out;
  out << "# Identified by birotor-identify --vehicle (" << (result.flight ? "flight" : "bench") << ", " << v.arm_count
      << " arms) from:\n";
  for (const std::string& s : sources) out << "#   " << s << "\n";
  out << "# Calibration fact used: every gauge scale held at the base file's (factory) value.\n";
  out << "# One-sigma uncertainties follow each fitted key; body keys, geometry and gauge scales\n";
  out << "# are the base file's.\n";
  for (size_t i = 0; i < result.arms.size(); ++i) {
    out << "# arm " << i + 1 << (result.flight ? ": free-flight" : ": clamped-arm") << " strain residual RMS "
        << std::setprecision(3) << result.arms[i].strain_rms_whitened << " sigma\n";
  }
  out << "vehicle:\n";
  out << "  name: " << v.name << "\n";
  out << std::setprecision(kFullPrecision);
  out << "  body_mass_kg: " << v.body_mass_kg << "\n";
  out << "  body_inertia_kg_m2: " << v.body_inertia_kg_m2 << "\n";
  out << "  gravity_m_s2: " << v.gravity_m_s2 << "\n";
  out << "  omega_max_rad_s: " << v.omega_max_rad_s << "\n";
  out << "  turbulence_std: " << v.turbulence_std << "\n";
  out << "  turbulence_corr_time_s: " << v.turbulence_corr_time_s << "\n";
  out << "  gauge_offset_std_rad: " << v.gauge_offset_std_rad << "\n";
  out << "  gauge_drift_psd_rad2_s: " << v.gauge_drift_psd_rad2_s << "\n";
  out << "  arms:\n";
  for (int i = 0; i < v.arm_count; ++i) {
    const size_t arm = static_cast<size_t>(i);
    WriteArm(out, v.arms[arm], arm < result.arms.size() ? &result.arms[arm] : nullptr);
  }
  return out.str();
}

}  // namespace birotor
