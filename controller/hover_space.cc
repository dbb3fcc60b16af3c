#include "controller/hover_space.h"

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

namespace birotor {
namespace {

// Bounds met within this share of the largest thrust involved (round-off of
// the projection) [1].
constexpr double kBoundTolerance = 1e-9;
// A set of active bounds whose Gram matrix has a pivot below this share of
// its largest diagonal entry is dependent (an equivalent smaller set is tried
// too) [1].
constexpr double kDependentPivot = 1e-10;

using Gram = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxArms, kMaxArms>;
using SpareVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxArms, 1>;

// Bits set in mask.
int BitCount(unsigned mask) {
  int count = 0;
  for (; mask != 0; mask &= mask - 1) ++count;
  return count;
}

}  // namespace

HoverSpace::HoverSpace(const VehicleDescription& vehicle, MultiArmControlMode mode,
                       const ArmForces<double>& hover_force_n)
    : rotor_count_(vehicle.arm_count), hover_force_n_(hover_force_n), max_force_n_(vehicle.arm_count) {
  for (int i = 0; i < rotor_count_; ++i) {
    max_force_n_(i) =
        vehicle.arms[static_cast<size_t>(i)].thrust_coeff_n_s2_rad2 * vehicle.omega_max_rad_s * vehicle.omega_max_rad_s;
  }
  const int first_row = mode == MultiArmControlMode::kFullyActuated ? kWrenchFx : kWrenchFz;
  const Eigen::MatrixXd controlled = WrenchAllocation(vehicle).bottomRows(kWrenchSize - first_row);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(controlled, Eigen::ComputeFullV);
  const int rank = static_cast<int>(svd.rank());
  spare_ = std::max(0, rotor_count_ - rank);
  null_basis_ = svd.matrixV().rightCols(spare_);
  if (mode == MultiArmControlMode::kFullyActuated && rank == kWrenchSize) {
    // f_lateral = W^T (W W^T)^-1 [m g, 0, 0]: thrusts making the weight sideways, no F_z, no torque.
    const Eigen::Vector3d weight_sideways(vehicle.TotalMass() * vehicle.gravity_m_s2, 0.0, 0.0);
    lateral_force_n_ = controlled.transpose() * (controlled * controlled.transpose()).ldlt().solve(weight_sideways);
  }
  if (rank == controlled.rows()) {
    // P [.., 1]: the controlled rows' pseudo-inverse on a unit torque (the last row).
    Eigen::VectorXd unit_torque = Eigen::VectorXd::Zero(controlled.rows());
    unit_torque(controlled.rows() - 1) = 1.0;
    torque_force_n_ = controlled.transpose() * (controlled * controlled.transpose()).ldlt().solve(unit_torque);
  }
}

bool HoverSpace::Nearest(const ArmForces<double>& low_n, const ArmForces<double>& high_n,
                         ArmForces<double>* hover_n) const {
  return NearestTo(hover_force_n_, low_n, high_n, hover_n);
}

bool HoverSpace::NearestTo(const ArmForces<double>& centre_n, const ArmForces<double>& low_n,
                           const ArmForces<double>& high_n, ArmForces<double>* hover_n) const {
  double scale_n = 1.0;
  bool hover_fits = true;
  for (int i = 0; i < rotor_count_; ++i) {
    scale_n = std::max({scale_n, std::fabs(high_n(i)), std::fabs(centre_n(i))});
    hover_fits = hover_fits && centre_n(i) >= low_n(i) && centre_n(i) <= high_n(i);
  }
  if (hover_fits) {
    if (hover_n != nullptr) *hover_n = centre_n;
    return true;
  }
  if (spare_ == 0) return false;
  // Bound j on y: row a_j and limit c_j with a_j y <= c_j; j = 2 i: f_i <=
  // high_i, j = 2 i + 1: f_i >= low_i.
  const auto row = [&](int j) -> Eigen::Matrix<double, 1, Eigen::Dynamic, Eigen::RowMajor, 1, kMaxArms> {
    return (j % 2 == 0 ? 1.0 : -1.0) * null_basis_.row(j / 2);
  };
  const auto limit = [&](int j) {
    const int i = j / 2;
    return j % 2 == 0 ? high_n(i) - centre_n(i) : centre_n(i) - low_n(i);
  };
  const int bounds = 2 * rotor_count_;
  const double tolerance_n = kBoundTolerance * scale_n;
  double best_norm = std::numeric_limits<double>::infinity();
  SpareVector best(spare_);
  for (unsigned mask = 1; mask < (1u << bounds); ++mask) {
    const int active = BitCount(mask);
    // Both bounds of one rotor are parallel: never independent.
    if (active > spare_ || (mask & (mask >> 1) & 0x555u) != 0) continue;
    Gram rows(active, spare_);
    SpareVector limits(active);
    for (int j = 0, k = 0; j < bounds; ++j) {
      if ((mask >> j & 1u) == 0) continue;
      rows.row(k) = row(j);
      limits(k++) = limit(j);
    }
    // Least-norm y on {A y = c}: y = A^T (A A^T)^-1 c.
    const Gram gram = rows * rows.transpose();
    const Eigen::LLT<Gram> factor(gram);
    if (factor.info() != Eigen::Success) continue;
    const double largest = gram.diagonal().maxCoeff();
    if (factor.matrixLLT().diagonal().minCoeff() <= std::sqrt(kDependentPivot * largest)) continue;
    const SpareVector y = rows.transpose() * factor.solve(limits);
    const double norm = y.squaredNorm();
    if (norm >= best_norm) continue;
    bool inside = true;
    for (int j = 0; j < bounds && inside; ++j) inside = row(j).dot(y) <= limit(j) + tolerance_n;
    if (!inside) continue;
    best_norm = norm;
    best = y;
  }
  if (!std::isfinite(best_norm)) return false;
  if (hover_n != nullptr) {
    *hover_n = centre_n + null_basis_ * best;
    // Round-off only (the bounds hold within the tolerance); min of max: a
    // box with low above high never gets here with a candidate inside.
    for (int i = 0; i < rotor_count_; ++i) (*hover_n)(i) = std::min(std::max((*hover_n)(i), low_n(i)), high_n(i));
  }
  return true;
}

void HoverSpace::ShareBox(const double* efficiency, double min_share, double max_share, ArmForces<double>* low_n,
                          ArmForces<double>* high_n) const {
  low_n->resize(rotor_count_);
  high_n->resize(rotor_count_);
  for (int i = 0; i < rotor_count_; ++i) {
    const double makes_n = std::max(0.0, efficiency[i]) * max_force_n_(i);
    (*low_n)(i) = min_share * makes_n;
    (*high_n)(i) = max_share * makes_n;
  }
}

bool HoverSpace::NearestWithinShares(const double* efficiency, double min_share, double max_share,
                                     ArmForces<double>* hover_n) const {
  ArmForces<double> low_n;
  ArmForces<double> high_n;
  ShareBox(efficiency, min_share, max_share, &low_n, &high_n);
  return Nearest(low_n, high_n, hover_n);
}

bool HoverSpace::LevelPitchesBothWays(const double* efficiency, double max_share, double torque_n_m) const {
  if (torque_force_n_.size() != rotor_count_) return false;
  ArmForces<double> low_n;
  ArmForces<double> high_n;
  ShareBox(efficiency, 0.0, max_share, &low_n, &high_n);
  for (double sign : {1.0, -1.0}) {
    const ArmForces<double> centre_n = hover_force_n_ + sign * torque_n_m * torque_force_n_;
    if (!NearestTo(centre_n, low_n, high_n, nullptr)) return false;
  }
  return true;
}

bool HoverSpace::NearestTiltedWithinShares(const double* efficiency, double min_share, double max_share,
                                           double max_tilt_rad, ArmForces<double>* hover_n, double* tilt_rad,
                                           double from_tilt_rad) const {
  if (lateral_force_n_.size() != rotor_count_) return false;
  ArmForces<double> low_n;
  ArmForces<double> high_n;
  ShareBox(efficiency, min_share, max_share, &low_n, &high_n);
  const int steps = static_cast<int>(std::floor(max_tilt_rad / kTiltStepRad + 1e-9));
  const int first = std::max(1, static_cast<int>(std::lround(from_tilt_rad / kTiltStepRad)));
  for (int k = first; k <= steps; ++k) {
    for (double sign : {1.0, -1.0}) {
      const double phi = sign * k * kTiltStepRad;
      const ArmForces<double> centre_n = std::cos(phi) * hover_force_n_ + std::sin(phi) * lateral_force_n_;
      if (!NearestTo(centre_n, low_n, high_n, hover_n)) continue;
      if (tilt_rad != nullptr) *tilt_rad = phi;
      return true;
    }
  }
  // A box without width (a dead rotor) holds at most a single tilt, which
  // the grid misses without a spare rotor.
  return spare_ == 0 && LeastTiltWithoutSpare(low_n, high_n, max_tilt_rad, from_tilt_rad, hover_n, tilt_rad);
}

bool HoverSpace::LeastTiltWithoutSpare(const ArmForces<double>& low_n, const ArmForces<double>& high_n,
                                       double max_tilt_rad, double from_tilt_rad, ArmForces<double>* hover_n,
                                       double* tilt_rad) const {
  double scale_n = 1.0;
  for (int i = 0; i < rotor_count_; ++i) scale_n = std::max(scale_n, std::fabs(high_n(i)));
  const double tolerance_n = kBoundTolerance * scale_n;
  const auto hover_at = [&](double phi) -> ArmForces<double> {
    return std::cos(phi) * hover_force_n_ + std::sin(phi) * lateral_force_n_;
  };
  const auto fits = [&](const ArmForces<double>& f) {
    for (int i = 0; i < rotor_count_; ++i) {
      if (!(f(i) >= low_n(i) - tolerance_n && f(i) <= high_n(i) + tolerance_n)) return false;
    }
    return true;
  };
  double best_rad = std::numeric_limits<double>::infinity();
  const auto consider = [&](double phi) {
    const double size = std::fabs(phi);
    if (size < from_tilt_rad || size > max_tilt_rad || size > std::fabs(best_rad)) return;
    if (size == std::fabs(best_rad) && phi < best_rad) return;  // the positive tilt first
    if (fits(hover_at(phi))) best_rad = phi;
  };
  consider(from_tilt_rad);
  consider(-from_tilt_rad);
  // Rotor i meets bound b where h_i cos(phi) + l_i sin(phi) = b, i.e.
  // r_i cos(phi - delta_i) = b with r_i = |(h_i, l_i)|, delta_i = atan2(l_i, h_i).
  for (int i = 0; i < rotor_count_; ++i) {
    const double radius_n = std::hypot(hover_force_n_(i), lateral_force_n_(i));
    if (radius_n <= tolerance_n) continue;
    const double delta_rad = std::atan2(lateral_force_n_(i), hover_force_n_(i));
    for (double bound_n : {low_n(i), high_n(i)}) {
      if (std::fabs(bound_n) > radius_n) continue;
      const double half_rad = std::acos(bound_n / radius_n);
      for (double phi : {delta_rad - half_rad, delta_rad + half_rad}) {
        consider(std::remainder(phi, 2.0 * M_PI));
      }
    }
  }
  if (!std::isfinite(best_rad)) return false;
  if (tilt_rad != nullptr) *tilt_rad = best_rad;
  if (hover_n != nullptr) {
    *hover_n = hover_at(best_rad);
    // Round-off only: the bounds hold within the tolerance.
    for (int i = 0; i < rotor_count_; ++i) (*hover_n)(i) = std::min(std::max((*hover_n)(i), low_n(i)), high_n(i));
  }
  return true;
}

}  // namespace birotor
