// Ground contact of a described vehicle (N arms): GroundContact
// (estimator/ground_contact.h, the birotor's rule and keys) fed with the
// thrusts' component along body z at phi = 0 and b_i = 0,
//   F_z = sum_i f_i cos theta_i   (n_i = [-sin theta_i, cos theta_i]),
// the support then N = M a_z - F_z with M = m + sum m_p,i. On the trirotor
// (theta = 0, -45, +45 deg) F_z at hover is 27.47 + 2 (14.32 cos 45 deg) =
// 47.7 N = M g. No LCM, no allocation.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "estimator/estimator_config.h"
#include "estimator/ground_contact.h"
#include "model/vehicle_description.h"

namespace birotor {

class MultiArmGroundContact {
 public:
  MultiArmGroundContact(const VehicleDescription& vehicle, const EkfOptions& options);

  // One IMU sample's specific force along body z [m/s^2] with the thrusts
  // f_0 .. f_(N-1) of the current estimate [N] (force_n null: the weight M g,
  // the hover thrust assumed before the first estimate).
  void Update(int64_t utime, double accel_z_m_s2, const double* force_n);
  // One POSE sample's height z [m]: GroundContact::OnPose.
  void OnPose(double z_m) { contact_.OnPose(z_m); }
  void Reset() { contact_.Reset(); }
  bool supported() const { return contact_.supported(); }
  // GroundContact::near_ground: in the air within ground_may_touch_m of the
  // height the ground last held the body.
  bool near_ground() const { return contact_.near_ground(); }
  // GroundContact::may_carry: near the ground with a support above the in-the-air threshold.
  bool may_carry() const { return contact_.may_carry(); }
  // GroundContact::has_been_supported: the ground has held the body since start-up.
  bool has_been_supported() const { return contact_.has_been_supported(); }
  // GroundContact::ReleasedSupportVarianceM2S4: the support that may still
  // carry the body after a time on the ground.
  double ReleasedSupportVarianceM2S4() const { return contact_.ReleasedSupportVarianceM2S4(); }
  // GroundContact::HeldRateVariance [rad^2/s^2].
  double HeldRateVariance(double predicted_rate_rad_s) const { return contact_.HeldRateVariance(predicted_rate_rad_s); }
  const GroundContact& contact() const { return contact_; }

 private:
  int arm_count_;
  double weight_n_;                         // M g [N]
  std::array<double, kMaxArms> cos_theta_;  // cos theta_i [1]
  GroundContact contact_;
};

}  // namespace birotor
