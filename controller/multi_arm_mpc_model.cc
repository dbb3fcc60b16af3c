#include "controller/multi_arm_mpc_model.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "model/multi_arm_dynamics.h"
#include "model/plant.h"
#include "model/rk4.h"

namespace birotor {

MultiArmMpcModel::MultiArmMpcModel(const VehicleDescription& vehicle) : vehicle_(vehicle) {
  const MultiArmHover hover = SolveMultiArmHover(vehicle);
  const int n = vehicle.arm_count;
  hover_deflection_rad_ = hover.deflection_rad.head(n);
  hover_force_n_ = hover.force_n.head(n);
  hover_speed_rad_s_.resize(n);
  for (int i = 0; i < n; ++i) {
    const double c_t = vehicle.arms[static_cast<size_t>(i)].thrust_coeff_n_s2_rad2;
    hover_speed_rad_s_(i) = std::sqrt(std::max(hover_force_n_(i), 0.0) / c_t);
  }
}

MultiArmMpcContext MultiArmMpcModel::NominalContext() const {
  MultiArmMpcContext context;
  context.efficiency = MultiArmMpcInputs::Ones(rotors());
  return context;
}

MultiArmMpcState MultiArmMpcModel::HoverState() const {
  MultiArmMpcState s = MultiArmMpcState::Zero(state_size());
  s.tail(rotors()) = hover_speed_rad_s_;
  return s;
}

MultiArmMpcState MultiArmMpcModel::Derivative(const MultiArmMpcState& s, const MultiArmMpcInputs& omega_cmd_rad_s,
                                              const MultiArmMpcContext& context) const {
  const int n = rotors();
  const int coordinates = kBodyCoordinates + n;
  MultiCoords<double> q = MultiCoords<double>::Zero(coordinates);
  MultiCoords<double> v = MultiCoords<double>::Zero(coordinates);
  q.head<3>() = s.segment<3>(kMpcX);
  v.head<3>() = s.segment<3>(kMpcXDot);
  ArmForces<double> force_n(n);
  for (int i = 0; i < n; ++i) {
    q(DeflectionIndex(i)) = hover_deflection_rad_(i);
    const double c_t = vehicle_.arms[static_cast<size_t>(i)].thrust_coeff_n_s2_rad2;
    force_n(i) = RotorThrust(c_t, s(MultiArmMpcOmegaIndex(i)), context.efficiency(i));
  }
  const MultiArmTerms<double> terms = ComputeMultiArmTerms<double>(vehicle_, q, v, force_n);
  const MultiCoords<double> rhs = terms.generalized_thrust - terms.coriolis - terms.gravity_spring;
  const Eigen::Matrix3d mass = terms.mass.topLeftCorner<3, 3>();
  const Eigen::Vector3d body_accel = mass.ldlt().solve(Eigen::Vector3d(rhs.head<3>())) + context.disturbance;
  MultiArmMpcState s_dot(state_size());
  s_dot.segment<3>(kMpcX) = s.segment<3>(kMpcXDot);
  s_dot.segment<3>(kMpcXDot) = body_accel;
  for (int i = 0; i < n; ++i) {
    const int w = MultiArmMpcOmegaIndex(i);
    s_dot(w) = (omega_cmd_rad_s(i) - s(w)) / vehicle_.arms[static_cast<size_t>(i)].motor_time_constant_s;
  }
  return s_dot;
}

MultiArmMpcState MultiArmMpcModel::Step(const MultiArmMpcState& s, const MultiArmMpcInputs& omega_cmd_rad_s,
                                        const MultiArmMpcContext& context, double dt_s) const {
  return Rk4Step(s, dt_s, [&](const MultiArmMpcState& x) { return Derivative(x, omega_cmd_rad_s, context); });
}

MultiArmMpcLinearStep MultiArmMpcModel::Linearize(const MultiArmMpcState& s0, const MultiArmMpcInputs& u0,
                                                  const MultiArmMpcContext& context, double dt_s) const {
  return CentralDifferenceStep<MultiArmMpcLinearStep>(
      s0, u0, [&](const MultiArmMpcState& s, const MultiArmMpcInputs& u) { return Step(s, u, context, dt_s); });
}

}  // namespace birotor
