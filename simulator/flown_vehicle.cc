#include "simulator/flown_vehicle.h"

#include "model/birotor_params.h"

namespace birotor {
namespace {

// value x changed / reference, computed as (value / reference) x changed so
// that a description equal to the reference takes the changed value exactly.
double Scaled(double value, double changed, double reference) { return value / reference * changed; }

}  // namespace

VehicleDescription FlownVehicle(const VehicleDescription& description, const VehicleDescription& scenario_vehicle) {
  const VehicleDescription reference = BirotorDescription(BirotorParams());
  const VehicleDescription& changed = scenario_vehicle;
  VehicleDescription flown = description;
  flown.body_mass_kg = Scaled(description.body_mass_kg, changed.body_mass_kg, reference.body_mass_kg);
  flown.body_inertia_kg_m2 =
      Scaled(description.body_inertia_kg_m2, changed.body_inertia_kg_m2, reference.body_inertia_kg_m2);
  flown.gravity_m_s2 = Scaled(description.gravity_m_s2, changed.gravity_m_s2, reference.gravity_m_s2);
  flown.omega_max_rad_s = Scaled(description.omega_max_rad_s, changed.omega_max_rad_s, reference.omega_max_rad_s);
  flown.turbulence_std = Scaled(description.turbulence_std, changed.turbulence_std, reference.turbulence_std);
  flown.turbulence_corr_time_s =
      Scaled(description.turbulence_corr_time_s, changed.turbulence_corr_time_s, reference.turbulence_corr_time_s);
  // The scenario's arms are a birotor's two equal arms: arm 1 carries them.
  const ArmDescription& changed_arm = changed.arms[0];
  const ArmDescription& reference_arm = reference.arms[0];
  for (int i = 0; i < description.arm_count; ++i) {
    const ArmDescription& arm = description.arms[static_cast<size_t>(i)];
    ArmDescription& out = flown.arms[static_cast<size_t>(i)];
    out.length_m = Scaled(arm.length_m, changed_arm.length_m, reference_arm.length_m);
    out.stiffness_n_m_rad =
        Scaled(arm.stiffness_n_m_rad, changed_arm.stiffness_n_m_rad, reference_arm.stiffness_n_m_rad);
    out.damping_n_m_s_rad =
        Scaled(arm.damping_n_m_s_rad, changed_arm.damping_n_m_s_rad, reference_arm.damping_n_m_s_rad);
    out.tip_mass_kg = Scaled(arm.tip_mass_kg, changed_arm.tip_mass_kg, reference_arm.tip_mass_kg);
    out.thrust_coeff_n_s2_rad2 =
        Scaled(arm.thrust_coeff_n_s2_rad2, changed_arm.thrust_coeff_n_s2_rad2, reference_arm.thrust_coeff_n_s2_rad2);
    out.motor_time_constant_s =
        Scaled(arm.motor_time_constant_s, changed_arm.motor_time_constant_s, reference_arm.motor_time_constant_s);
  }
  return flown;
}

}  // namespace birotor
