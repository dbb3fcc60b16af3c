#include "controller/multi_arm_law.h"

#include <algorithm>
#include <cmath>

namespace birotor {

MultiArmLaw::MultiArmLaw(const VehicleDescription& vehicle, const ControllerParams& gains, const MultiArmHover& hover,
                         const EfficiencyParams& spare)
    : gains_(gains),
      dt_s_(1.0 / gains.rate_hz),
      gravity_m_s2_(vehicle.gravity_m_s2),
      total_mass_kg_(vehicle.TotalMass()),
      pitch_inertia_kg_m2_(vehicle.body_inertia_kg_m2),
      hover_force_n_(hover.force_n),
      allocator_(vehicle, MultiArmControlModeFor(vehicle)),
      hover_space_(vehicle, allocator_.mode(), hover_force_n_),
      spare_min_share_(spare.spare_min_share),
      spare_max_share_(spare.spare_max_share),
      feasible_share_(1.0 / spare.feasibility_margin),
      hover_tilt_limit_rad_(spare.spare_hover_tilt_rad),
      tilted_min_share_(std::max(spare.spare_tilted_min_share, spare.spare_min_share)),
      base_force_n_(hover_force_n_),
      tilt_dwell_s_(spare.infeasible_s),
      tilt_limit_rad_(gains.max_tilt_rad) {
  for (int i = 0; i < vehicle.arm_count; ++i) {
    const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
    pitch_inertia_kg_m2_ += arm.tip_mass_kg * arm.length_m * arm.length_m;
  }
}

void MultiArmLaw::Reset() {
  position_integral_m_s_.setZero();
  tilt_integral_rad_s_ = 0.0;
  saturated_ = false;
}

Eigen::Vector3d MultiArmLaw::Wrench(const BodyState& body, const ReferencePoint& reference, bool integrate) {
  const double g = gravity_m_s2_;
  accel_des_m_s2_ = PositionLoopAcceleration(gains_, dt_s_, body, reference, integrate, &position_integral_m_s_);
  if (mode() == MultiArmControlMode::kFullyActuated && tilt_limit_rad_ < gains_.max_tilt_rad) {
    const double max_lateral_m_s2 = g * std::tan(std::max(tilt_limit_rad_, 0.0));
    accel_des_m_s2_.x() = std::clamp(accel_des_m_s2_.x(), -max_lateral_m_s2, max_lateral_m_s2);
  }
  const double cos_phi = std::cos(std::clamp(body.phi_rad, -1.2, 1.2));
  Eigen::Vector3d wrench;  // [F_x, F_z, torque], body frame [N, N, N m]
  double phi_des_rad = base_tilt_rad_;
  if (base_pins_rotor_) {
    // No F_x left (a rotor held at 0 N by the tilt): move as a birotor
    // does, tilting the rotors' one force direction off the base's.
    const double move_rad = TiltForAcceleration(gains_, g, accel_des_m_s2_).phi_des_rad;
    phi_des_rad = std::clamp(base_tilt_rad_ + move_rad, -tilt_limit_rad_, tilt_limit_rad_);
  }
  if (mode() == MultiArmControlMode::kTiltToMove) {
    const TiltTarget tilt = TiltForAcceleration(gains_, g, accel_des_m_s2_);
    phi_des_rad = std::clamp(tilt.phi_des_rad, -tilt_limit_rad_, tilt_limit_rad_);
    wrench(kWrenchFx) = 0.0;
    wrench(kWrenchFz) = total_mass_kg_ * tilt.vertical_m_s2 / cos_phi;
  } else {
    // [F_x; F_z] = R(phi)^T m (a_des + g e_z), R(phi) = [cos, -sin; sin, cos].
    const double sin_phi = std::sin(body.phi_rad);
    const Eigen::Vector2d world_n = total_mass_kg_ * Eigen::Vector2d(accel_des_m_s2_.x(), accel_des_m_s2_.y() + g);
    wrench(kWrenchFx) = std::cos(body.phi_rad) * world_n.x() + sin_phi * world_n.y();
    wrench(kWrenchFz) = -sin_phi * world_n.x() + std::cos(body.phi_rad) * world_n.y();
  }
  wrench(kWrenchTorque) =
      pitch_inertia_kg_m2_ * TiltLoopAcceleration(gains_, dt_s_, phi_des_rad, body, integrate, &tilt_integral_rad_s_);
  return wrench;
}

MultiArmRotorCommand MultiArmLaw::Update(const BodyState& body, const ReferencePoint& reference,
                                         const RotorEfficiencies& efficiency) {
  const ArmForces<double>& base_n = HoverBase(efficiency);
  base_pins_rotor_ = base_tilt_rad_ != 0.0 && !hover_space_.redundant() && AnyRotorOut(efficiency);
  Eigen::Vector3d wrench = Wrench(body, reference, !saturated_);
  // The hover thrusts carry the weight: m g [sin phi_base, cos phi_base] in the body frame.
  const double weight_n = total_mass_kg_ * gravity_m_s2_;
  if (base_tilt_rad_ != 0.0) wrench(kWrenchFx) -= weight_n * std::sin(base_tilt_rad_);
  wrench(kWrenchFz) -= base_tilt_rad_ != 0.0 ? weight_n * std::cos(base_tilt_rad_) : weight_n;
  if (base_pins_rotor_) wrench(kWrenchFx) = 0.0;  // no F_x: the tilt moves the vehicle (Wrench)
  MultiArmRotorCommand command = allocator_.Allocate(base_n, wrench, efficiency);
  if (base_pins_rotor_) command.saturated = !MakesLiftAndTorque(base_n, wrench, command);
  saturated_ = command.saturated;
  return command;
}

bool MultiArmLaw::AnyRotorOut(const RotorEfficiencies& efficiency) const {
  for (int i = 0; i < hover_force_n_.size(); ++i) {
    if (!(efficiency[static_cast<size_t>(i)] > 0.0)) return true;
  }
  return false;
}

bool MultiArmLaw::MakesLiftAndTorque(const ArmForces<double>& base_n, const Eigen::Vector3d& wrench_change,
                                     const MultiArmRotorCommand& command) const {
  const int n = static_cast<int>(base_n.size());
  ArmForces<double> made_n(n);
  for (int i = 0; i < n; ++i) made_n(i) = command.force_n[static_cast<size_t>(i)];
  const Eigen::Vector3d short_n = allocator_.allocation() * (base_n - made_n) + wrench_change;
  const double tolerance_n = kMadeTolerance * total_mass_kg_ * gravity_m_s2_;
  return std::fabs(short_n(kWrenchFz)) <= tolerance_n && std::fabs(short_n(kWrenchTorque)) <= tolerance_n;
}

bool MultiArmLaw::AnyHover(const RotorEfficiencies& efficiency, double max_tilt_rad, double* least_tilt_rad) const {
  const double* e = efficiency.data();
  *least_tilt_rad = 0.0;
  // The healthy vehicle: its least-norm hover within HoverBase's first box, one solve.
  if (hover_space_.NearestWithinShares(e, spare_min_share_, spare_max_share_, nullptr)) return true;
  const double widest = std::max(spare_max_share_, feasible_share_);
  if (hover_space_.NearestWithinShares(e, spare_min_share_, widest, nullptr)) return true;
  double tilt_rad = 0.0;
  if (!hover_space_.NearestTiltedWithinShares(e, spare_min_share_, widest, max_tilt_rad, nullptr, &tilt_rad)) {
    return false;
  }
  *least_tilt_rad = std::fabs(tilt_rad);
  return true;
}

bool MultiArmLaw::LevelPitchesBothWays(const RotorEfficiencies& efficiency) const {
  if (!hover_space_.redundant()) return true;
  return hover_space_.LevelPitchesBothWays(efficiency.data(), feasible_share_, pitch_inertia_kg_m2_ * kPitchProbeRadS2);
}

const ArmForces<double>& MultiArmLaw::HoverBase(const RotorEfficiencies& efficiency) {
  base_tilt_rad_ = 0.0;
  base_is_hover_ = true;
  if (!hover_space_.redundant()) {
    return tilted_without_spare_ ? LevelOrTiltedBase(efficiency) : hover_force_n_;
  }
  base_is_hover_ = false;
  const double* e = efficiency.data();
  // Levelling for a descent (tilt limit 0) holds no tilted hover.
  const double max_tilt_rad = std::min(hover_tilt_limit_rad_, tilt_limit_rad_);
  double least_tilt_rad = 0.0;
  if (!AnyHover(efficiency, max_tilt_rad, &least_tilt_rad)) {
    base_is_hover_ = true;
    return hover_force_n_;  // no hover held: the allocator scales it down (the infeasible descent)
  }
  for (double max_share : {spare_max_share_, feasible_share_}) {
    if (hover_space_.NearestWithinShares(e, spare_min_share_, max_share, &base_force_n_)) return base_force_n_;
    // Tilted: the thrust holding the lateral force up off its lower bound first (room for F_x both ways).
    for (double min_share : {tilted_min_share_, spare_min_share_}) {
      if (hover_space_.NearestTiltedWithinShares(e, min_share, max_share, max_tilt_rad, &base_force_n_, &base_tilt_rad_,
                                                 least_tilt_rad)) {
        return base_force_n_;
      }
    }
  }
  base_tilt_rad_ = 0.0;
  base_is_hover_ = true;
  return hover_force_n_;  // no hover held: the allocator scales it down (the infeasible descent)
}

const ArmForces<double>& MultiArmLaw::LevelOrTiltedBase(const RotorEfficiencies& efficiency) {
  const double* e = efficiency.data();
  if (!hover_space_.tilts() || hover_space_.NearestWithinShares(e, 0.0, feasible_share_, nullptr)) {
    level_out_of_reach_s_ = 0.0;
    return hover_force_n_;
  }
  // The cascade tilts once the level hover has been out of reach for
  // infeasible_s: a dying rotor passes through the tilted hovers in that
  // time and its descent starts level (the trirotor, rotor 3 dead: peak
  // tilt 0.50-0.57 rad without the dwell, docs/controller.md). Not once a
  // rotor is out: only the tilted hover pinning it holds the vehicle (the
  // dwell cost 0.09 m of overshoot).
  level_out_of_reach_s_ += dt_s_;
  if (level_out_of_reach_s_ < tilt_dwell_s_ && !AnyRotorOut(efficiency)) {
    return hover_force_n_;
  }
  // Levelling for a descent (tilt limit 0) holds no tilted hover.
  const double max_tilt_rad = std::min(hover_tilt_limit_rad_, tilt_limit_rad_);
  for (double min_share : {tilted_min_share_, spare_min_share_}) {
    if (hover_space_.NearestTiltedWithinShares(e, min_share, spare_max_share_, max_tilt_rad, &base_force_n_,
                                               &base_tilt_rad_)) {
      base_is_hover_ = false;
      return base_force_n_;
    }
  }
  base_tilt_rad_ = 0.0;
  return hover_force_n_;  // no hover held: the allocator scales it down (the infeasible descent)
}

}  // namespace birotor
