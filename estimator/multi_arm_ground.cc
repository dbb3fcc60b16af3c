#include "estimator/multi_arm_ground.h"

#include <cmath>

namespace birotor {

MultiArmGroundContact::MultiArmGroundContact(const VehicleDescription& vehicle, const EkfOptions& options)
    : arm_count_(vehicle.arm_count),
      weight_n_(vehicle.TotalMass() * vehicle.gravity_m_s2),
      cos_theta_{},
      contact_(vehicle.TotalMass(), vehicle.gravity_m_s2, options) {
  for (int i = 0; i < arm_count_; ++i) {
    cos_theta_[static_cast<size_t>(i)] = std::cos(vehicle.arms[static_cast<size_t>(i)].thrust_angle_rad);
  }
}

void MultiArmGroundContact::Update(int64_t utime, double accel_z_m_s2, const double* force_n) {
  double thrust_z_n = weight_n_;
  if (force_n != nullptr) {
    thrust_z_n = 0.0;
    for (int i = 0; i < arm_count_; ++i) thrust_z_n += force_n[i] * cos_theta_[static_cast<size_t>(i)];
  }
  contact_.Update(utime, accel_z_m_s2, thrust_z_n);
}

}  // namespace birotor
