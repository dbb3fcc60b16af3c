// The cascaded position and pitch law shared by the simulator's autopilot and
// the controller service: from a body state and a position reference to the
// thrust each rotor must make. Pure, allocation-free; how the forces become
// rotor speeds (nominal map or force feedback) is the caller's choice.
#pragma once

#include <Eigen/Core>
#include <algorithm>

#include "controller/controller_params.h"
#include "controller/reference_point.h"
#include "model/birotor_params.h"
#include "samples/rotor_count.h"

namespace birotor {

// Rigid-body state the law needs, world frame.
struct BodyState {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();    // x, z [m]
  Eigen::Vector2d velocity_m_s = Eigen::Vector2d::Zero();  // x_dot, z_dot [m/s]
  double phi_rad = 0.0;                                    // tilt [rad]
  double phi_dot_rad_s = 0.0;                              // pitch rate [rad/s]
};

// Thrust each rotor must make [N] (rotor 1, rotor 2), as a total and a
// difference f2 - f1 (for an allocation within the rotors' limits), and the
// world acceleration the outer loop asked for [m/s^2].
struct RotorForces {
  double force_n[kBirotorRotors] = {0.0, 0.0};
  double total_force_n = 0.0;       // f1 + f2 [N]
  double force_difference_n = 0.0;  // f2 - f1 [N]
  Eigen::Vector2d accel_des_m_s2 = Eigen::Vector2d::Zero();
};

// The cascade's stages as functions, shared by PositionAttitudeLaw and the
// N-arm autopilot (controller/multi_arm_law.h). integrate false: the
// integral holds.
//
// Outer loop (world): a_des = a_ref + Kp e_p + Kd e_v + Ki int(e_p), the
// integral clamped to max_integral / Ki [m s].
Eigen::Vector2d PositionLoopAcceleration(const ControllerParams& gains, double dt_s, const BodyState& state,
                                         const ReferencePoint& reference, bool integrate,
                                         Eigen::Vector2d* position_integral_m_s);
// Tilt that turns the thrust towards a_des: vertical = max(g + a_z, 0.1 g)
// [m/s^2], phi_des = atan2(-a_x, vertical) clamped to max_tilt [rad].
struct TiltTarget {
  double vertical_m_s2 = 0.0;
  double phi_des_rad = 0.0;
};
TiltTarget TiltForAcceleration(const ControllerParams& gains, double gravity_m_s2,
                               const Eigen::Vector2d& accel_des_m_s2);
// Inner loop (pitch): alpha_des = Kp_phi e_phi - Kd_phi phi_dot + Ki_phi
// int(e_phi) [rad/s^2], the integral clamped to max_attitude_integral / Ki_phi.
double TiltLoopAcceleration(const ControllerParams& gains, double dt_s, double phi_des_rad, const BodyState& state,
                            bool integrate, double* tilt_integral_rad_s);

class PositionAttitudeLaw {
 public:
  // hover_force_n: per-rotor feed-forward thrust at hover (the equilibrium
  // solution of the nominal vehicle).
  PositionAttitudeLaw(const BirotorParams& vehicle, const ControllerParams& gains, double hover_force_n);

  // One control period dt_s = 1 / rate_hz:
  //   a_des = a_ref + Kp e_p + Kd e_v + Ki int(e_p)                    (world)
  //   phi_des = atan2(-a_des_x, g + a_des_z), F = F_hover (g + a_des_z) / (g cos phi)
  //   alpha_des = Kp_phi e_phi - Kd_phi phi_dot + Ki_phi int(e_phi)
  //   f_1,2 = F / 2 -+ J_eff alpha_des / (2 L)    (tau_phi = L (f2 - f1), eq. 3.12)
  // with J_eff = J + 2 m_p L^2 (rigid arms).
  // integrate false: the integrators hold (anti-windup: the caller's
  // commands saturated in the previous period).
  RotorForces Update(const BodyState& state, const ReferencePoint& reference, bool integrate = true) {
    return Update(state, reference, integrate, integrate);
  }
  // The same with the two integrators held separately: integrate_tilt false
  // holds the pitch integrator only (a descent whose total is limited but
  // whose pitch torque is not).
  RotorForces Update(const BodyState& state, const ReferencePoint& reference, bool integrate_position,
                     bool integrate_tilt);

  // Clears both integrators (e.g. after a numerical guard).
  void Reset();
  // Clears the position integrator only (entering a controlled descent: what
  // it learnt tracking the setpoint would tilt the descent).
  void ResetPositionIntegral() { position_integral_m_s_.setZero(); }
  // The tilt target's bound from now on: min(max_tilt_rad, gains' max_tilt)
  // [rad] (a controlled descent flies level; 0 levels the vehicle).
  void LimitTilt(double max_tilt_rad) { tilt_limit_rad_ = std::min(max_tilt_rad, gains_.max_tilt_rad); }

 private:
  BirotorParams vehicle_;
  ControllerParams gains_;
  double hover_total_force_n_;
  double dt_s_;
  Eigen::Vector2d position_integral_m_s_ = Eigen::Vector2d::Zero();  // int(e_p) [m s]
  double tilt_integral_rad_s_ = 0.0;                                 // int(e_phi) [rad s]
  double tilt_limit_rad_;                                            // bound of phi_des [rad]
};

// Pitch inertia of the rigid vehicle, J_eff = J + 2 m_p L^2 [kg m^2]: the
// body and the two tip masses at the arm length (0.086 for the reference vehicle).
inline double RigidPitchInertiaKgM2(const BirotorParams& p) {
  return p.body_inertia_kg_m2 + 2.0 * p.tip_mass_kg * p.arm_length_m * p.arm_length_m;
}

// Rotor speed that makes force_n with thrust scale mu (f = mu c_T omega^2):
// omega = sqrt(max(f, 0) / (mu c_T)), clipped to [0, omega_max] [rad/s].
// *saturated (optional) is set when the clip changed the value.
double RotorSpeedForThrust(const BirotorParams& vehicle, double force_n, double thrust_scale,
                           bool* saturated = nullptr);
// The same for one rotor of any vehicle: its c_T [N s^2/rad^2] and omega_max [rad/s].
double RotorSpeedForThrust(double thrust_coeff_n_s2_rad2, double omega_max_rad_s, double force_n, double thrust_scale,
                           bool* saturated = nullptr);

}  // namespace birotor
