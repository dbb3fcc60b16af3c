// Whether the ground holds the vehicle, judged from the support force it must
// be providing. The accelerometer reads the specific force a_z along body z;
// in flight the rotors carry the whole vehicle, M a_z = F_z (M = m + sum m_p,i,
// F_z the thrusts' component along body z: f1 + f2 on the birotor,
// sum f_i cos theta_i on a vehicle description), while on the ground the
// support adds N = M a_z - F_z (M g - F_z at rest). One class for the birotor
// EKF and the N-arm EKF. No LCM, no allocation.
#pragma once

#include <cstdint>

#include "estimator/estimator_config.h"
#include "model/birotor_params.h"

namespace birotor {

class GroundContact {
 public:
  // total_mass_kg: M [kg]; gravity_m_s2: g [m/s^2].
  GroundContact(double total_mass_kg, double gravity_m_s2, const EkfOptions& options);
  GroundContact(const BirotorParams& params, const EkfOptions& options)
      : GroundContact(params.TotalMass(), params.gravity_m_s2, options) {}

  // One IMU sample (specific force along body z [m/s^2]) with the current
  // thrust estimate along body z, F_z [N]. N, clamped to +-M g per sample (a reading
  // spike cannot flip the contact), is low-passed (first order, time constant
  // ground_contact_filter_s, lengthened for a noisy accelerometer: see
  // TimeConstantS) and compared with the hysteresis thresholds.
  void Update(int64_t utime, double accel_z_m_s2, double thrust_z_n);
  void Reset();

  bool supported() const { return supported_; }
  // The filter's time constant for a sample interval dt_s [s]: the option, or
  // longer when the accelerometer noise (accel_noise_m_s2) would leave the
  // filtered N noisier than a sixth of the hysteresis band [s].
  double TimeConstantS(double dt_s) const;
  double support_force_n() const { return support_force_n_; }  // low-passed N [N]

 private:
  double total_mass_kg_;
  double on_n_, off_n_, filter_s_;
  double support_noise_n_;  // M sigma_a: one sigma of N per sample [N]
  double weight_n_;         // M g: each sample's N is clamped to +-this [N]
  bool has_sample_ = false;
  int64_t last_utime_ = 0;
  double support_force_n_ = 0;
  bool supported_ = false;
};

}  // namespace birotor
