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
  // One POSE sample's height z [m] (world frame, up): the ground's height
  // is z while the contact holds; afterwards z tells whether the body is
  // still within ground_may_touch_m of it.
  void OnPose(double z_m);
  void Reset() {
    contact_.Reset();
    has_been_supported_ = false;
    has_ground_height_ = false;
    near_ground_ = false;
  }
  bool supported() const { return contact_.supported(); }
  // In the air after a time on the ground, the support may still carry the
  // filtered N (up to ground_contact_off_n when the contact lets go at
  // F_z > M g - off_n, before the body lifts): the accelerometer then reads
  // a_z = (F_z + N) / M with N unknown in [0, N_f], so its a_z variance
  // gains (N_bound / M)^2 [m^2/s^4], N_bound = max(N_f, 0); within
  // ground_may_touch_m of the ground's height (POSE) the body may touch it
  // below the contact's threshold, N_bound = max(N_f, ground_contact_on_n).
  // 0 until the body was first on the ground (a start in the air is
  // unchanged).
  double ReleasedSupportVarianceM2S4() const {
    if (!has_been_supported_) return 0.0;
    const double bound_n =
        near_ground_ ? std::max(contact_.support_force_n(), may_touch_n_) : std::max(contact_.support_force_n(), 0.0);
    const double a = bound_n / total_mass_kg_;
    return a * a;
  }
  bool near_ground() const { return near_ground_; }
  const GroundContact& contact() const { return contact_; }

 private:
  int arm_count_;
  double total_mass_kg_;  // M [kg]
  double weight_n_;       // M g [N]
  bool has_been_supported_ = false;
  double may_touch_m_;  // ground_may_touch_m [m]
  double may_touch_n_;  // ground_contact_on_n: the support the contact may miss [N]
  bool has_ground_height_ = false;
  double ground_height_m_ = 0.0;            // POSE z while the contact last held [m]
  bool near_ground_ = false;                // the newest POSE within may_touch_m_ of it
  std::array<double, kMaxArms> cos_theta_;  // cos theta_i [1]
  GroundContact contact_;
};

}  // namespace birotor
