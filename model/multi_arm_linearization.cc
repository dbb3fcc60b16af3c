#include "model/multi_arm_linearization.h"

#include <ceres/jet.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>

#include "model/multi_arm_dynamics.h"

namespace birotor {
namespace {

using HoverJet = ceres::Jet<double, 2 * kMaxArms>;
using LinearJet = ceres::Jet<double, 2 * kMaxCoordinates + kMaxArms>;

// Rows of tau - G balanced at hover (see SolveMultiArmHover).
std::vector<int> BalancedRows(const VehicleDescription& vehicle) {
  std::vector<int> rows;
  if (vehicle.arm_count > 2) rows.push_back(kX);
  rows.push_back(kZ);
  rows.push_back(kPhi);
  for (int i = 0; i < vehicle.arm_count; ++i) rows.push_back(DeflectionIndex(i));
  return rows;
}

// Static residual rows of tau - G at q = [0, 0, 0, b], v = 0; unknowns [b; f].
Eigen::VectorXd StaticResidual(const VehicleDescription& vehicle, const Eigen::VectorXd& unknowns,
                               Eigen::MatrixXd* jacobian) {
  const int arms = vehicle.arm_count, n = CoordinateCount(vehicle);
  MultiCoords<HoverJet> q = MultiCoords<HoverJet>::Zero(n), v = MultiCoords<HoverJet>::Zero(n);
  ArmForces<HoverJet> f(arms);
  for (int i = 0; i < arms; ++i) {
    q(DeflectionIndex(i)) = HoverJet(unknowns(i), i);
    f(i) = HoverJet(unknowns(arms + i), arms + i);
  }
  const MultiArmTerms<HoverJet> terms = ComputeMultiArmTerms<HoverJet>(vehicle, q, v, f);
  const std::vector<int> rows = BalancedRows(vehicle);
  Eigen::VectorXd value(static_cast<int>(rows.size()));
  jacobian->resize(value.size(), 2 * arms);
  for (int r = 0; r < value.size(); ++r) {
    const HoverJet net =
        terms.generalized_thrust(rows[static_cast<size_t>(r)]) - terms.gravity_spring(rows[static_cast<size_t>(r)]);
    value(r) = net.a;
    jacobian->row(r) = net.v.head(2 * arms).transpose();
  }
  return value;
}

}  // namespace

MultiArmHover SolveMultiArmHover(const VehicleDescription& vehicle) {
  const int arms = vehicle.arm_count;
  MultiArmHover hover;
  // The rigid allocation (model/vehicle_description.h, tip weights' moment
  // included) is the first guess; Newton adds the deflections.
  hover.allocation_force_n = Eigen::Map<const Eigen::VectorXd>(SolveHover(vehicle).thrust_n.data(), vehicle.arm_count);
  Eigen::VectorXd unknowns(2 * arms);
  for (int i = 0; i < arms; ++i) {
    const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
    const double f = hover.allocation_force_n(i);
    unknowns(i) =
        (arm.ThrustLeverM() * f - arm.tip_mass_kg * vehicle.gravity_m_s2 * arm.length_m * std::cos(arm.angle_rad)) /
        arm.stiffness_n_m_rad;
    unknowns(arms + i) = f;
  }
  for (int iteration = 0; iteration < 50; ++iteration) {
    Eigen::MatrixXd jacobian;
    const Eigen::VectorXd value = StaticResidual(vehicle, unknowns, &jacobian);
    hover.residual = value.cwiseAbs().maxCoeff();
    if (hover.residual < 1e-12) {
      hover.converged = true;
      break;
    }
    unknowns -= Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(jacobian).solve(value);
  }
  hover.deflection_rad = unknowns.head(arms);
  hover.force_n = unknowns.tail(arms);
  return hover;
}

MultiArmLinearModel LinearizeMultiArm(const VehicleDescription& vehicle, const Eigen::VectorXd& q0,
                                      const Eigen::VectorXd& v0, const Eigen::VectorXd& force0_n) {
  const int n = CoordinateCount(vehicle), arms = vehicle.arm_count;
  MultiCoords<LinearJet> q(n), v(n);
  ArmForces<LinearJet> f(arms);
  for (int i = 0; i < n; ++i) {
    q(i) = LinearJet(q0(i), i);
    v(i) = LinearJet(v0(i), n + i);
  }
  for (int i = 0; i < arms; ++i) f(i) = LinearJet(force0_n(i), 2 * n + i);
  const MultiCoords<LinearJet> acc = MultiArmAcceleration<LinearJet>(vehicle, q, v, f);
  MultiArmLinearModel model;
  model.a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  model.b = Eigen::MatrixXd::Zero(2 * n, arms);
  model.a.topRightCorner(n, n).setIdentity();
  for (int i = 0; i < n; ++i) {
    model.a.row(n + i) = acc(i).v.head(2 * n).transpose();
    model.b.row(n + i) = acc(i).v.segment(2 * n, arms).transpose();
  }
  return model;
}

MultiArmLinearModel LinearizeMultiArmAtHover(const VehicleDescription& vehicle, const MultiArmHover& hover) {
  const int n = CoordinateCount(vehicle);
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(n);
  q0.tail(vehicle.arm_count) = hover.deflection_rad;
  return LinearizeMultiArm(vehicle, q0, Eigen::VectorXd::Zero(n), hover.force_n);
}

Eigen::MatrixXd AugmentMultiArmWithForces(const MultiArmLinearModel& model) {
  const Eigen::Index states = model.a.rows(), forces = model.b.cols();
  Eigen::MatrixXd aug = Eigen::MatrixXd::Zero(states + forces, states + forces);
  aug.topLeftCorner(states, states) = model.a;
  aug.topRightCorner(states, forces) = model.b;
  return aug;
}

std::vector<std::string> MultiArmStateNames(int arm_count) {
  std::vector<std::string> q = {"x", "z", "phi"};
  for (int i = 1; i <= arm_count; ++i) q.push_back("b" + std::to_string(i));
  std::vector<std::string> names = q;
  for (const std::string& name : q) names.push_back(name + "_dot");
  for (int i = 1; i <= arm_count; ++i) names.push_back("f" + std::to_string(i));
  return names;
}

}  // namespace birotor
