// Whether the ground holds the vehicle, judged from the support force it must
// be providing. The accelerometer reads the specific force a_z along body z;
// in flight the rotors carry the whole vehicle, M a_z = f1 + f2 (M = m + 2 m_p),
// while on the ground the support adds N = M a_z - (f1 + f2) (M g - F at rest).
// No LCM, no allocation.
#pragma once

#include <cstdint>

#include "estimator/estimator_config.h"
#include "model/birotor_params.h"

namespace birotor {

class GroundContact {
 public:
  GroundContact(const BirotorParams& params, const EkfOptions& options);

  // One IMU sample (specific force along body z [m/s^2]) with the current
  // thrust estimate f1 + f2 [N]. N, clamped to +-M g per sample (a reading
  // spike cannot flip the contact), is low-passed (first order, time constant
  // ground_contact_filter_s, lengthened for a noisy accelerometer: see
  // TimeConstantS) and compared with the hysteresis thresholds.
  void Update(int64_t utime, double accel_z_m_s2, double total_force_n);
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
