#include "controller/mpc_model.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "model/birotor_dynamics.h"
#include "model/equilibrium.h"
#include "model/plant.h"
#include "model/rk4.h"

namespace birotor {

MpcPredictionModel::MpcPredictionModel(const BirotorParams& vehicle) : vehicle_(vehicle) {
  const Equilibrium hover = SolveHoverEquilibrium(vehicle);
  hover_deflection_rad_[0] = hover.deflection_rad[0];
  hover_deflection_rad_[1] = hover.deflection_rad[1];
  hover_force_n_ = 0.5 * (hover.force_n[0] + hover.force_n[1]);
}

MpcState MpcPredictionModel::Derivative(const MpcState& s, const Eigen::Vector2d& omega_cmd_rad_s,
                                        const MpcModelContext& context) const {
  Coords<double> q, v;
  q << s(kMpcX), s(kMpcZ), s(kMpcPhi), hover_deflection_rad_[0], hover_deflection_rad_[1];
  v << s(kMpcXDot), s(kMpcZDot), s(kMpcPhiDot), 0.0, 0.0;
  const double f1 = RotorThrust(vehicle_, s(kMpcOmega1), context.thrust_scale(0));
  const double f2 = RotorThrust(vehicle_, s(kMpcOmega2), context.thrust_scale(1));
  const DynamicsTerms<double> terms = ComputeDynamicsTerms<double>(vehicle_, q, v, f1, f2);
  const Coords<double> rhs = terms.generalized_thrust - terms.coriolis - terms.gravity_spring;
  // Rigid arms: the b rows carry the constraint torques; the body rows alone
  // with the top-left block of M are the constrained dynamics.
  const Eigen::Matrix3d mass = terms.mass.topLeftCorner<3, 3>();
  const Eigen::Vector3d body_accel = mass.ldlt().solve(rhs.head<3>()) + context.disturbance;
  MpcState s_dot;
  s_dot.segment<3>(kMpcX) = s.segment<3>(kMpcXDot);
  s_dot.segment<3>(kMpcXDot) = body_accel;
  const double tau_m = vehicle_.motor_time_constant_s;
  s_dot(kMpcOmega1) = (omega_cmd_rad_s(0) - s(kMpcOmega1)) / tau_m;
  s_dot(kMpcOmega2) = (omega_cmd_rad_s(1) - s(kMpcOmega2)) / tau_m;
  return s_dot;
}

MpcState MpcPredictionModel::Step(const MpcState& s, const Eigen::Vector2d& omega_cmd_rad_s,
                                  const MpcModelContext& context, double dt_s) const {
  return Rk4Step(s, dt_s, [&](const MpcState& x) { return Derivative(x, omega_cmd_rad_s, context); });
}

MpcLinearStep MpcPredictionModel::Linearize(const MpcState& s0, const Eigen::Vector2d& u0,
                                            const MpcModelContext& context, double dt_s) const {
  MpcLinearStep out;
  // Central differences: steps ~1e-6 of each variable's scale (m, rad, rad/s
  // for speeds of hundreds) keep truncation and rounding both near 1e-9.
  for (int j = 0; j < kMpcStateSize; ++j) {
    const double h = (j >= kMpcOmega1) ? 1e-3 : 1e-6;
    MpcState plus = s0, minus = s0;
    plus(j) += h;
    minus(j) -= h;
    out.a.col(j) = (Step(plus, u0, context, dt_s) - Step(minus, u0, context, dt_s)) / (2.0 * h);
  }
  for (int j = 0; j < kMpcInputSize; ++j) {
    const double h = 1e-3;
    Eigen::Vector2d plus = u0, minus = u0;
    plus(j) += h;
    minus(j) -= h;
    out.b.col(j) = (Step(s0, plus, context, dt_s) - Step(s0, minus, context, dt_s)) / (2.0 * h);
  }
  out.c = Step(s0, u0, context, dt_s) - out.a * s0 - out.b * u0;
  return out;
}

}  // namespace birotor
