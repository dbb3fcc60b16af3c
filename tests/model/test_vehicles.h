// The vehicles the N-arm model tests use, built in code: the reference
// birotor as a VehicleDescription and a three-rotor test vehicle. One place,
// so a loaded description file can replace them later.
#pragma once

#include <cmath>

#include "model/vehicle_description.h"
#include "model/vehicle_params.h"

namespace birotor {
namespace test_vehicles {

inline double Degrees(double angle_deg) { return angle_deg * M_PI / 180.0; }

// Every arm of a description with the reference parameters of one arm.
inline ArmDescription ArmFromParams(const VehicleParams& p, double angle_rad, double thrust_angle_rad) {
  ArmDescription arm;
  arm.angle_rad = angle_rad;
  arm.length_m = p.arm_length_m;
  arm.thrust_angle_rad = thrust_angle_rad;
  arm.stiffness_n_m_rad = p.arm_stiffness_n_m_rad;
  arm.damping_n_m_s_rad = p.arm_damping_n_m_s_rad;
  arm.tip_mass_kg = p.tip_mass_kg;
  arm.thrust_coeff_n_s2_rad2 = p.thrust_coeff_n_s2_rad2;
  arm.motor_time_constant_s = p.motor_time_constant_s;
  return arm;
}

inline VehicleDescription BodyFromParams(const VehicleParams& p) {
  VehicleDescription vehicle;
  vehicle.body_mass_kg = p.body_mass_kg;
  vehicle.body_inertia_kg_m2 = p.body_inertia_kg_m2;
  vehicle.gravity_m_s2 = p.gravity_m_s2;
  return vehicle;
}

// The birotor of the reference file: arm 1 along body -x, arm 2 along +x, thrust up.
inline VehicleDescription Birotor(const VehicleParams& p = VehicleParams()) {
  VehicleDescription vehicle = BodyFromParams(p);
  vehicle.name = "birotor";
  vehicle.arm_count = 2;
  vehicle.arms[0] = ArmFromParams(p, M_PI, 0.0);
  vehicle.arms[1] = ArmFromParams(p, 0.0, 0.0);
  return vehicle;
}

// A fully actuated three-rotor test vehicle with the reference arms: arms at
// alpha = 210, -30, 90 deg, thrust tilted by theta = 10, -60, 40 deg, so the
// hover wrench [F_x, F_z, torque] has a unique positive solution (27.07,
// 17.40, 16.13 N) and every lever |l_i| / L = |cos(alpha_i - theta_i)| is at
// least 0.64. three_gauges = false takes arm 3's gauge away (thesis 7.3.2).
inline VehicleDescription Trirotor(bool three_gauges = true, const VehicleParams& p = VehicleParams()) {
  VehicleDescription vehicle = BodyFromParams(p);
  vehicle.name = three_gauges ? "trirotor" : "trirotor, no gauge on arm 3";
  vehicle.arm_count = 3;
  vehicle.arms[0] = ArmFromParams(p, Degrees(210.0), Degrees(10.0));
  vehicle.arms[1] = ArmFromParams(p, Degrees(-30.0), Degrees(-60.0));
  vehicle.arms[2] = ArmFromParams(p, Degrees(90.0), Degrees(40.0));
  vehicle.arms[2].has_gauge = three_gauges;
  return vehicle;
}

}  // namespace test_vehicles
}  // namespace birotor
