// The prediction model of the N-input model predictive controller: a planar
// body with N rotors (model/vehicle_description.h), its arms held rigid at
// their hover deflection (as controller/mpc_model.h holds the birotor's), a
// first-order motor lag per rotor and rotor speed commands as inputs. The
// physics is model/'s: the rows x, z, phi of the N-arm Euler-Lagrange terms
// (model/multi_arm_dynamics.h), the thrust map and the motor lag of
// model/plant.h. Fixed maximum sizes: no heap allocation at any N.
#pragma once

#include <Eigen/Core>

#include "controller/mpc_model.h"
#include "model/multi_arm_linearization.h"
#include "model/vehicle_description.h"

namespace birotor {

// State s = [x, z, phi, x_dot, z_dot, phi_dot, omega_1 .. omega_N]: the body
// rows keep the birotor's names (kMpcX .. kMpcPhiDot of mpc_model.h), rotor i's
// speed [rad/s] is at MultiArmMpcOmegaIndex(i).
inline constexpr int kMaxMultiArmMpcStateSize = kMpcBodyStates + kMaxArms;
constexpr int MultiArmMpcOmegaIndex(int rotor) { return kMpcBodyStates + rotor; }
inline int MultiArmMpcStateSize(const VehicleDescription& vehicle) { return kMpcBodyStates + vehicle.arm_count; }

using MultiArmMpcState = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxMultiArmMpcStateSize, 1>;
using MultiArmMpcStateMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxMultiArmMpcStateSize, kMaxMultiArmMpcStateSize>;
using MultiArmMpcInputMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxMultiArmMpcStateSize, kMaxArms>;
// One entry per rotor: commands [rad/s], efficiencies [1], thrusts [N].
using MultiArmMpcInputs = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxArms, 1>;

// What the prediction holds constant over the horizon besides the commands.
struct MultiArmMpcContext {
  // e_i: rotor i makes e_i c_T,i omega_i^2 (1: the nominal map; FORCE's
  // thrust_scale for force feedback). Size N.
  MultiArmMpcInputs efficiency;
  // Unmodelled accelerations (x, z [m/s^2], pitch [rad/s^2]) added to the model's.
  Eigen::Vector3d disturbance = Eigen::Vector3d::Zero();
};

// One discrete step s+ = A s + B u + c, exact at the point it was taken about.
struct MultiArmMpcLinearStep {
  MultiArmMpcStateMatrix a;  // d s+ / d s, (6 + N) x (6 + N)
  MultiArmMpcInputMatrix b;  // d s+ / d u, (6 + N) x N
  MultiArmMpcState c;        // F(s0, u0) - A s0 - B u0
};

// The birotor model's fixed-size step (controller/mpc_model.h) as an N = 2
// step: the same numbers, for the one QP (controller/mpc_qp.h).
inline MultiArmMpcLinearStep Generalized(const MpcLinearStep& step) {
  MultiArmMpcLinearStep out;
  out.a = step.a;
  out.b = step.b;
  out.c = step.c;
  return out;
}

class MultiArmMpcModel {
 public:
  explicit MultiArmMpcModel(const VehicleDescription& vehicle);

  // s_dot = [v; M33^-1 (tau - C - G)_33 + d; (u_i - omega_i) / tau_m,i] with
  // q = [x, z, phi, b_hover], v = [x_dot, z_dot, phi_dot, 0]: the body rows of
  // model/multi_arm_dynamics.h with the arms rigid (M33: the top-left block
  // of M, the b rows carry the constraint torques), thrust
  // f_i = e_i c_T,i omega_i^2. The command is not clamped (the QP's bounds are).
  MultiArmMpcState Derivative(const MultiArmMpcState& s, const MultiArmMpcInputs& omega_cmd_rad_s,
                              const MultiArmMpcContext& context) const;
  // One RK4 step over dt_s [s] with the commands held.
  MultiArmMpcState Step(const MultiArmMpcState& s, const MultiArmMpcInputs& omega_cmd_rad_s,
                        const MultiArmMpcContext& context, double dt_s) const;
  // Jacobians of Step about (s0, u0) by central differences
  // (CentralDifferenceStep of controller/mpc_model.h, the birotor's routine).
  MultiArmMpcLinearStep Linearize(const MultiArmMpcState& s0, const MultiArmMpcInputs& u0,
                                  const MultiArmMpcContext& context, double dt_s) const;

  // The level vehicle at rest with every rotor at its hover speed.
  MultiArmMpcState HoverState() const;
  // Hover thrust f_i [N] and speed sqrt(f_i / c_T,i) [rad/s] (e = 1) of the
  // deflected equilibrium (SolveMultiArmHover).
  const MultiArmMpcInputs& hover_force_n() const { return hover_force_n_; }
  const MultiArmMpcInputs& hover_speed_rad_s() const { return hover_speed_rad_s_; }
  // A context with every efficiency 1 and no disturbance.
  MultiArmMpcContext NominalContext() const;
  const VehicleDescription& vehicle() const { return vehicle_; }
  int rotors() const { return vehicle_.arm_count; }
  int state_size() const { return kMpcBodyStates + vehicle_.arm_count; }

 private:
  VehicleDescription vehicle_;
  MultiArmMpcInputs hover_deflection_rad_;
  MultiArmMpcInputs hover_force_n_;
  MultiArmMpcInputs hover_speed_rad_s_;
};

}  // namespace birotor
