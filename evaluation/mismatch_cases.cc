// Issue 36's flights. Reference values (config/reference_vehicle.yaml):
// m 4.0 kg, m_p 0.28812 kg, L 0.25 m, J 0.05 kg m^2, k 2628 N m/rad,
// d 0.25 N m s/rad, c_T 4.6e-5 N s^2/rad^2, tau_m 0.035 s, gauge scale 1,
// turbulence 0.01, strain noise 2e-5 rad.
#include "evaluation/mismatch_cases.h"

namespace birotor {
namespace {

// The ground phase of the shipped files (rest 3 s, spool-up 1 s) before the
// gentle move, with 4 s more so the move and its 5 s after are all flown.
std::vector<std::string> GroundStart(std::vector<std::string> overrides) {
  overrides.insert(overrides.begin(), {"ground.enabled=true", "scenario.duration_s=19"});
  return overrides;
}

// A calm hover: turbulence a fifth of the default 0.01; 15 s like gentle.
std::vector<std::string> CalmHover(std::vector<std::string> overrides) {
  overrides.insert(overrides.begin(), {"scenario.duration_s=15", "vehicle.turbulence_std=0.002"});
  return overrides;
}

}  // namespace

// Factors: m x1.10, m_p x0.85, L x1.05, J x1.20, k x0.90, d x1.30,
// c_T x1.08, tau_m x1.25, gauge scale x0.90 (arm 1) and x1.07 (arm 2).
std::vector<std::string> EveryParameterDifferentOverrides() {
  return {"vehicle.body_mass_kg=4.4",
          "vehicle.tip_mass_kg=0.244902",
          "vehicle.arm_length_m=0.2625",
          "vehicle.body_inertia_kg_m2=0.06",
          "vehicle.arm_stiffness_n_m_rad=2365.2",
          "vehicle.arm_damping_n_m_s_rad=0.325",
          "vehicle.thrust_coeff_n_s2_rad2=4.968e-5",
          "vehicle.motor_time_constant_s=0.04375",
          "gauge.scale=[0.9, 1.07]"};
}

const std::vector<MismatchCase>& VehicleMismatchCases() {
  static const std::vector<MismatchCase> cases = {
      {"stiffness +15 %", "gentle", {"vehicle.arm_stiffness_n_m_rad=3022.2"}},
      {"stiffness -15 %", "gentle", {"vehicle.arm_stiffness_n_m_rad=2233.8"}},
      {"stiffness +20 %", "gentle", {"vehicle.arm_stiffness_n_m_rad=3153.6"}},
      {"stiffness -20 %", "gentle", {"vehicle.arm_stiffness_n_m_rad=2102.4"}},
      {"body +10 %, airborne", "gentle", {"vehicle.body_mass_kg=4.4"}},
      {"body +15 %, airborne", "gentle", {"vehicle.body_mass_kg=4.6"}},
      {"body +10 %, ground start", "gentle", GroundStart({"vehicle.body_mass_kg=4.4"})},
      {"body +15 %, ground start", "gentle", GroundStart({"vehicle.body_mass_kg=4.6"})},
      {"tip mass +10 %", "gentle", {"vehicle.tip_mass_kg=0.316932"}},
      {"tip mass -10 %", "gentle", {"vehicle.tip_mass_kg=0.259308"}},
      {"tip mass +20 %", "gentle", {"vehicle.tip_mass_kg=0.345744"}},
      {"tip mass -20 %", "gentle", {"vehicle.tip_mass_kg=0.230496"}},
      {"tip mass +10 %, calm hover", "hover", CalmHover({"vehicle.tip_mass_kg=0.316932"})},
      {"tip mass -10 %, calm hover", "hover", CalmHover({"vehicle.tip_mass_kg=0.259308"})},
      {"tip mass +20 %, calm hover", "hover", CalmHover({"vehicle.tip_mass_kg=0.345744"})},
      {"tip mass -20 %, calm hover", "hover", CalmHover({"vehicle.tip_mass_kg=0.230496"})},
      {"gauge noise x2, 50 us stamp jitter",
       "gentle",
       {"sensors.strain.noise_rad=4.0e-5", "sensors.strain.stamp_jitter_s=5.0e-5"}},
      {"gauge scale 0.7 on arm 1", "gentle", {"gauge.scale=[0.7, 1.0]"}},
      {"c_T -15 %", "gentle", {"vehicle.thrust_coeff_n_s2_rad2=3.91e-5"}},
      {"every parameter 5-30 % off", "gentle", EveryParameterDifferentOverrides()},
  };
  return cases;
}

const std::vector<MismatchCase>& MatchingVehicleCases() {
  static const std::vector<MismatchCase> cases = {{"hover", "hover", {}},
                                                  {"gentle", "gentle", {}},
                                                  {"aggressive", "aggressive", {}},
                                                  {"thrust_loss", "thrust_loss", {}}};
  return cases;
}

}  // namespace birotor
