// The gauge-offset combinations a redundant vehicle cannot tell from its
// rotor forces in flight, for the N-arm EKF's Schmidt hold
// (estimator/multi_arm_ekf_fusion.h, LeadingGainHold). docs/estimator.md,
// "A vehicle with more rotors than the body pins".
//
// In free flight the rigid body (accelerometer, gyro) sees the rotor forces
// only through the wrench W f, W's column i = [-sin theta_i; cos theta_i;
// l_i] (body F_x, F_z, moment). A force change d f in W's null space (N - 3
// combinations on a fully actuated vehicle with N > 3 rotors) moves no body
// sensor; each arm bends by db_i = l_i df_i / k_eff,i (static, k_eff,i = k_i -
// m_p,i g L_i sin alpha_i: the spring less the tip weight's moment slope),
// and offsets de_i = -db_i leave every calibrated reading b_i + e_i where it
// was. A constant force there and a constant offset pattern are the same
// readings: in hover nothing but the offsets' prior tells them apart, and an
// estimate free to move along the pattern wanders (docs/estimator.md). The
// hold's keep = I - U U^T removes these patterns U (orthonormal, on the
// gauged arms) from the gain's offset rows.
#pragma once

#include <Eigen/Core>
#include <Eigen/SVD>
#include <cmath>

#include "estimator/multi_arm_ekf_fusion.h"
#include "model/vehicle_description.h"

namespace birotor {

// The hold for the description's offsets e_1..e_N (inactive when the wrench
// has no null space: N <= 3, or every pattern vanishes on the gauged arms).
template <int N>
LeadingGainHold<N> UnseenOffsetHold(const VehicleDescription& vehicle) {
  Eigen::Matrix<double, 3, N> wrench;  // rows F_x, F_z, moment [N, N, N m per N]
  for (int i = 0; i < N; ++i) {
    const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
    wrench.col(i) << -std::sin(arm.thrust_angle_rad), std::cos(arm.thrust_angle_rad), arm.ThrustLeverM();
  }
  const Eigen::JacobiSVD<Eigen::Matrix<double, 3, N>> svd(wrench, Eigen::ComputeFullV);
  const Eigen::Matrix<double, 3, 1> singular = svd.singularValues().template head<3>();
  constexpr double kRelativeRank = 1e-9;
  int rank = 0;
  for (int k = 0; k < 3 && k < N; ++k) rank += singular(k) > kRelativeRank * singular(0);
  LeadingGainHold<N> hold;
  Eigen::Matrix<double, N, N> patterns = Eigen::Matrix<double, N, N>::Zero();  // orthonormalised columns
  int count = 0;
  for (int k = rank; k < N; ++k) {
    Eigen::Matrix<double, N, 1> pattern = Eigen::Matrix<double, N, 1>::Zero();
    for (int i = 0; i < N; ++i) {
      const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
      if (!arm.has_gauge) continue;
      const double stiffness =
          arm.stiffness_n_m_rad - arm.tip_mass_kg * vehicle.gravity_m_s2 * arm.length_m * std::sin(arm.angle_rad);
      pattern(i) = arm.ThrustLeverM() * svd.matrixV()(i, k) / stiffness;  // rad per N of the null force
    }
    const double unreduced = pattern.norm();
    for (int j = 0; j < count; ++j) pattern -= patterns.col(j).dot(pattern) * patterns.col(j);  // Gram-Schmidt
    const double norm = pattern.norm();
    if (norm <= kRelativeRank * unreduced || unreduced == 0.0) continue;
    patterns.col(count++) = pattern / norm;
  }
  hold.active = count > 0;
  hold.keep -= patterns * patterns.transpose();
  return hold;
}

}  // namespace birotor
