// The shape of a planar vehicle with N elastic arms: one type every room can
// use to ask how many rotors there are and where they push. Plain data, SI
// units. The birotor of the reference file is the case N = 2 (BirotorDescription).
//
// Frames (docs/vehicle-description.md): body x right, body z up, angles
// positive in the sense of the tilt phi (turning body +x towards +z). Arm i is
// hinged at the body centre through a torsional spring; undeflected it points
// along e_i = [cos alpha_i, sin alpha_i] (body frame). Its tip carries the
// lumped mass m_p,i and a rotor whose thrust, undeflected, points along
// u_i = [-sin theta_i, cos theta_i] (theta_i = 0: body up). A deflection b_i
// turns both e_i and u_i by b_i, so in the world frame
//   p_i = p + L_i R(phi + b_i) e_i,   n_i = R(phi + b_i) u_i.
// The thrust's moment about the hinge, per newton, is the lever
//   l_i = L_i (e_i x u_i) = L_i cos(alpha_i - theta_i)   [m],
// which is what a gauge on arm i can see of f_i (l_i = 0: the gauge sees nothing).
#pragma once

#include <array>
#include <cmath>
#include <string>

namespace birotor {

// The most arms a description may have (the wire's per-rotor fault bits).
inline constexpr int kMaxArms = 6;
// The reference birotor's arm count (the fixed-size birotor messages).
inline constexpr int kBirotorArmCount = 2;

// One elastic arm, its hinge, its tip mass, its rotor and its gauge.
struct ArmDescription {
  double angle_rad = 0.0;                  // alpha_i: undeflected arm direction in the body frame [rad]
  double length_m = 0.25;                  // L_i: hinge (body centre) to rotor axis [m]
  double thrust_angle_rad = 0.0;           // theta_i: thrust direction from body up, undeflected [rad]
  int spin = 1;                            // +1 counter-clockwise seen from the thrust side, -1 clockwise
  double stiffness_n_m_rad = 2628.0;       // k_i: hinge torsional stiffness [N m/rad]
  double damping_n_m_s_rad = 0.25;         // d_i: hinge viscous damping [N m s/rad]
  double tip_mass_kg = 0.28812;            // m_p,i: motor, propeller and arm lumped at the tip [kg]
  double thrust_coeff_n_s2_rad2 = 4.6e-5;  // c_T,i: nominal map f = c_T omega^2 [N s^2/rad^2]
  double motor_time_constant_s = 0.035;    // tau_m,i: first-order speed response [s]
  bool has_gauge = true;                   // a strain gauge measures b_i
  double gauge_scale = 1.0;                // s_i: the gauge reads s_i b_i + o_i [1]
  double gauge_offset_rad = 0.0;           // o_i at power-up, if known [rad]

  // l_i = L_i cos(alpha_i - theta_i): hinge moment per newton of thrust [m].
  double ThrustLeverM() const { return length_m * std::cos(angle_rad - thrust_angle_rad); }
};

// A planar body with arm_count elastic arms.
struct VehicleDescription {
  std::string name = "birotor";
  int arm_count = kBirotorArmCount;
  std::array<ArmDescription, kMaxArms> arms{};  // arms[0 .. arm_count)
  double body_mass_kg = 4.0;                    // m: body without the tip masses [kg]
  double body_inertia_kg_m2 = 0.05;             // J: body about its centre (y axis) [kg m^2]
  double gravity_m_s2 = 9.81;                   // g [m/s^2]
  double omega_max_rad_s = 1200.0;              // every rotor's command clamp [0, omega_max] [rad/s]
  double turbulence_std = 0.01;                 // eta: relative thrust turbulence, std [1]
  double turbulence_corr_time_s = 0.1;          // eta: Gauss-Markov correlation time [s]
  double gauge_offset_std_rad = 5.0e-5;         // how well each o_i is known before a tare [rad]
  double gauge_drift_psd_rad2_s = 1.0e-10;      // random walk of each o_i in flight [rad^2/s]

  // m + sum_i m_p,i [kg].
  double TotalMass() const {
    double total = body_mass_kg;
    for (int i = 0; i < arm_count; ++i) total += arms[static_cast<size_t>(i)].tip_mass_kg;
    return total;
  }
  int GaugeCount() const {
    int n = 0;
    for (int i = 0; i < arm_count; ++i) n += arms[static_cast<size_t>(i)].has_gauge ? 1 : 0;
    return n;
  }
};

}  // namespace birotor
