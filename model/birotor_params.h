// The parameters of the closed-form birotor model (thesis eq. 3.10-3.14;
// reference vehicle of docs/reference-vehicle.md): two equal arms along body
// -x and +x with shared scalars. Plain data, SI units. Not a vehicle type of
// its own: a room holds its vehicle as a VehicleDescription
// (model/vehicle_description.h) and derives these, once and only for a
// description that is a birotor, by BirotorModelOf / ToBirotorParams. The
// birotor's closed-form dynamics, the EKF, the cascade and the MPC run on them.
#pragma once

#include "samples/rotor_count.h"

namespace birotor {

struct BirotorParams {
  double body_mass_kg = 4.0;               // m: body mass
  double tip_mass_kg = 0.28812;            // m_p: lumped motor+prop+arm mass at each tip
  double arm_length_m = 0.25;              // L: hinge to rotor axis
  double body_inertia_kg_m2 = 0.05;        // J: body inertia about its centre (y axis)
  double arm_stiffness_n_m_rad = 2628.0;   // k: torsional stiffness of each strain-gauge hinge
  double arm_damping_n_m_s_rad = 0.25;     // d: viscous damping of each hinge
  double gravity_m_s2 = 9.81;              // g
  double thrust_coeff_n_s2_rad2 = 4.6e-5;  // c_T: nominal thrust map f = c_T omega^2
  double motor_time_constant_s = 0.035;    // tau_m: first-order rotor speed response
  double omega_max_rad_s = 1200.0;         // command clamp [0, omega_max]
  double turbulence_std = 0.01;            // eta: std of the relative thrust turbulence
  double turbulence_corr_time_s = 0.1;     // eta: Gauss-Markov correlation time

  // Strain-gauge calibration (shared/spec/gauges.md, "Parameter keys"): a
  // gauge reads b_meas_i = s_i b_i + o_i; the estimator uses
  // b_i = (b_meas_i - o_i) / s_i. Defaults: the ideal gauge.
  double gauge_scale[kBirotorRotors] = {1.0, 1.0};       // s_i [1]
  double gauge_offset_rad[kBirotorRotors] = {0.0, 0.0};  // o_i at power-up, if known [rad]
  double gauge_offset_std_rad = 5.0e-5;                  // how well o_i is known before a tare [rad]
  double gauge_drift_psd_rad2_s = 1.0e-10;               // random walk of o_i in flight [rad^2/s]

  // Total mass m + 2 m_p [kg].
  double TotalMass() const { return body_mass_kg + 2.0 * tip_mass_kg; }
  // Thrust per rotor that holds the level vehicle in hover, g (m + 2 m_p) / 2 [N]
  // (thesis section 3.3.3; the exact equilibrium adds a 1/cos(b) factor).
  double HoverForceN() const { return 0.5 * gravity_m_s2 * TotalMass(); }
};

}  // namespace birotor
