// The prediction model of the model predictive controller: the planar body
// with its arms held rigid at their hover deflection (the 65/80 Hz arm modes
// are far above what a 100 Hz controller can act on) and a first-order motor
// lag per rotor, with rotor speed commands as inputs and each rotor's thrust
// f_i = thrust_scale_i c_T omega_i^2. The physics is model/'s: the rows x, z,
// phi of the Euler-Lagrange terms (model/birotor_dynamics.h) with b = b_hover,
// b_dot = 0, the thrust map and the motor lag of model/plant.h. No allocation.
#pragma once

#include <Eigen/Core>

#include "model/birotor_params.h"
#include "samples/rotor_count.h"

namespace birotor {

// Named indices of the prediction state.
enum MpcStateIndex : int {
  kMpcX = 0,       // [m], world
  kMpcZ = 1,       // [m], world, up
  kMpcPhi = 2,     // tilt [rad]
  kMpcXDot = 3,    // [m/s]
  kMpcZDot = 4,    // [m/s]
  kMpcPhiDot = 5,  // [rad/s]
  kMpcOmega1 = 6,  // rotor 1 speed [rad/s]
  kMpcOmega2 = 7,  // rotor 2 speed [rad/s]
};
constexpr int kMpcStateSize = 8;
// Body states x .. phi_dot ahead of the rotor speeds, at any rotor count.
inline constexpr int kMpcBodyStates = 6;
constexpr int kMpcInputSize = 2;  // rotor speed commands [rad/s]
using MpcState = Eigen::Matrix<double, kMpcStateSize, 1>;
using MpcStateMatrix = Eigen::Matrix<double, kMpcStateSize, kMpcStateSize>;
using MpcInputMatrix = Eigen::Matrix<double, kMpcStateSize, kMpcInputSize>;

// What the prediction holds constant over the horizon besides the commands.
struct MpcModelContext {
  Eigen::Vector2d thrust_scale = Eigen::Vector2d::Ones();  // mu_i [1]
  // Unmodelled accelerations (x, z [m/s^2], pitch [rad/s^2]) added to the model's.
  Eigen::Vector3d disturbance = Eigen::Vector3d::Zero();
};

// One discrete step s+ = A s + B u + c, exact at the point it was taken about.
struct MpcLinearStep {
  MpcStateMatrix a;  // d s+ / d s [1, s, ...]
  MpcInputMatrix b;  // d s+ / d u
  MpcState c;        // offset: F(s0, u0) - A s0 - B u0
};

// s+ = A s + B u + c about (s0, u0) of a discrete step(s, u) by central
// differences: steps ~1e-6 of each variable's scale (m, rad, and 1e-3 rad/s
// for rotor speeds of hundreds, states kMpcBodyStates.. and every input) keep
// truncation and rounding both near 1e-9; c = step(s0, u0) - A s0 - B u0.
// Generic over the state and input types: the birotor's fixed-size model and
// the N-rotor model (controller/multi_arm_mpc_model.h) share this routine and
// each keep their own arithmetic.
template <typename LinearStep, typename State, typename Inputs, typename StepFunction>
LinearStep CentralDifferenceStep(const State& s0, const Inputs& u0, const StepFunction& step) {
  const int ns = static_cast<int>(s0.size()), nu = static_cast<int>(u0.size());
  LinearStep out;
  out.a.resize(ns, ns);
  out.b.resize(ns, nu);
  for (int j = 0; j < ns; ++j) {
    const double h = (j >= kMpcBodyStates) ? 1e-3 : 1e-6;
    State plus = s0, minus = s0;
    plus(j) += h;
    minus(j) -= h;
    out.a.col(j) = (step(plus, u0) - step(minus, u0)) / (2.0 * h);
  }
  for (int j = 0; j < nu; ++j) {
    const double h = 1e-3;
    Inputs plus = u0, minus = u0;
    plus(j) += h;
    minus(j) -= h;
    out.b.col(j) = (step(s0, plus) - step(s0, minus)) / (2.0 * h);
  }
  out.c = step(s0, u0) - out.a * s0 - out.b * u0;
  return out;
}

class MpcPredictionModel {
 public:
  explicit MpcPredictionModel(const BirotorParams& vehicle);

  // s_dot = [v; M33^-1 (tau - C - G)_33 + d; (u - omega) / tau_m], the rows x,
  // z, phi of thesis eq. 3.14 with the arms rigid (M33: the top-left block of M).
  MpcState Derivative(const MpcState& s, const Eigen::Vector2d& omega_cmd_rad_s, const MpcModelContext& context) const;
  // One RK4 step over dt_s with the commands held.
  MpcState Step(const MpcState& s, const Eigen::Vector2d& omega_cmd_rad_s, const MpcModelContext& context,
                double dt_s) const;
  // Jacobians of Step about (s0, u0) by central differences (CentralDifferenceStep).
  MpcLinearStep Linearize(const MpcState& s0, const Eigen::Vector2d& u0, const MpcModelContext& context,
                          double dt_s) const;

  // Per-rotor thrust that holds the level vehicle still [N] (the hover equilibrium's).
  double hover_force_n() const { return hover_force_n_; }
  const BirotorParams& vehicle() const { return vehicle_; }

 private:
  BirotorParams vehicle_;
  double hover_deflection_rad_[kBirotorRotors] = {0.0, 0.0};
  double hover_force_n_ = 0.0;
};

}  // namespace birotor
