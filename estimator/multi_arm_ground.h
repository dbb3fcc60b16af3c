// Ground contact of a described vehicle (N arms): GroundContact
// (estimator/ground_contact.h, the birotor's rule and keys) fed with the
// thrusts' component along body z at phi = 0 and b_i = 0,
//   F_z = sum_i f_i cos theta_i   (n_i = [-sin theta_i, cos theta_i]),
// the support then N = M a_z - F_z with M = m + sum m_p,i. On the trirotor
// (theta = 0, -45, +45 deg) F_z at hover is 27.47 + 2 (14.32 cos 45 deg) =
// 47.7 N = M g. No LCM, no allocation.
#pragma once

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
  void Reset() {
    contact_.Reset();
    has_been_supported_ = false;
  }
  bool supported() const { return contact_.supported(); }
  // In the air after a time on the ground, the support may still carry the
  // filtered N (up to ground_contact_off_n when the contact lets go at
  // F_z > M g - off_n, before the body lifts): the accelerometer then reads
  // a_z = (F_z + N) / M with N unknown in [0, N_f], so its a_z variance
  // gains (max(N_f, 0) / M)^2 [m^2/s^4]. 0 until the body was first on the
  // ground (a start in the air is unchanged).
  double ReleasedSupportVarianceM2S4() const {
    if (!has_been_supported_ || !(contact_.support_force_n() > 0.0)) return 0.0;
    const double a = contact_.support_force_n() / total_mass_kg_;
    return a * a;
  }
  const GroundContact& contact() const { return contact_; }

 private:
  int arm_count_;
  double total_mass_kg_;  // M [kg]
  double weight_n_;       // M g [N]
  bool has_been_supported_ = false;
  std::array<double, kMaxArms> cos_theta_;  // cos theta_i [1]
  GroundContact contact_;
};

}  // namespace birotor
