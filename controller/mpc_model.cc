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
  return CentralDifferenceStep<MpcLinearStep>(
      s0, u0, [&](const MpcState& s, const Eigen::Vector2d& u) { return Step(s, u, context, dt_s); });
}

}  // namespace birotor
