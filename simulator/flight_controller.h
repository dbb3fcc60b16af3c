// The simulator's autopilot: a cascaded PD controller with integral action
// that tracks a position reference by commanding rotor speeds through the
// NOMINAL thrust map omega = sqrt(f / c_T). It sees the true rigid-body state
// (a perfect state estimate) but knows nothing of s_i or eta_i.
#pragma once

#include "model/plant.h"
#include "simulator/scenario.h"
#include "simulator/trajectory.h"

namespace birotor {

struct RotorCommand {
  double omega_cmd_rad_s[2] = {0.0, 0.0};
};

class FlightController {
 public:
  // hover_force_n: per-rotor feed-forward thrust at hover (the equilibrium
  // solution of the nominal vehicle).
  FlightController(const VehicleParams& vehicle, const ControllerParams& params, double hover_force_n);

  // One control period dt_s = 1 / rate_hz.
  //   a_des = a_ref + Kp e_p + Kd e_v + Ki int(e_p)                    (world)
  //   phi_des = atan2(-a_des_x, g + a_des_z), F = M (g + a_des_z) / cos(phi)
  //   alpha_des = Kp_phi e_phi - Kd_phi phi_dot + Ki_phi int(e_phi)
  //   f_1,2 = F / 2 -+ J_eff alpha_des / (2 L)    (tau_phi = L (f2 - f1), eq. 3.12)
  // with M = m + 2 m_p and J_eff = J + 2 m_p L^2 (rigid arms).
  RotorCommand Update(const PlantState& state, const ReferencePoint& reference);

 private:
  VehicleParams vehicle_;
  ControllerParams params_;
  double hover_total_force_n_;
  double dt_s_;
  Eigen::Vector2d position_integral_m_s_ = Eigen::Vector2d::Zero();  // int(e_p) [m s]
  double tilt_integral_rad_s_ = 0.0;                                 // int(e_phi) [rad s]
};

}  // namespace birotor
