// Whether the ground holds the vehicle, judged from the support force it must
// be providing. The accelerometer reads the specific force a_z along body z;
// in flight the rotors carry the whole vehicle, M a_z = F_z (M = m + sum m_p,i,
// F_z the thrusts' component along body z: f1 + f2 on the birotor,
// sum f_i cos theta_i on a vehicle description), while on the ground the
// support adds N = M a_z - F_z (M g - F_z at rest). One class for the birotor
// EKF and the N-arm EKF. No LCM, no allocation.
#pragma once

#include <cmath>
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
  // TimeConstantS) from 0 at the first sample (the air) and compared with
  // the hysteresis thresholds.
  void Update(int64_t utime, double accel_z_m_s2, double thrust_z_n);
  // One POSE sample's height z [m] (world frame, up): the ground's height
  // is z while the contact holds (from ground_may_touch_after_s on: a
  // rest); afterwards z tells whether the body is still within
  // ground_may_touch_m of it.
  void OnPose(double z_m);
  void Reset();

  bool supported() const { return supported_; }
  // The ground has held the body since start-up (or the last Reset).
  bool has_been_supported() const { return has_been_supported_; }
  // In the air within ground_may_touch_m of the height the ground last held
  // the body (POSE; false without POSE or with the band off, 0 m).
  bool near_ground() const { return near_ground_ && !supported_; }
  // near_ground, and ground_may_touch_after_s or longer since the contact
  // let go: the body may touch the ground with a support below the
  // contact's threshold. False in the lift-off's first
  // ground_may_touch_after_s, whose accelerometer is read at its full
  // weight (that is where a payload shows).
  bool may_touch() const;
  // near_ground with the filtered support N_f above ground_contact_off_n
  // (the in-the-air threshold) but below the contact's: the ground may be
  // carrying part of the weight, by an amount the IMU cannot tell from a
  // thrust no gauge reads.
  bool may_carry() const { return near_ground() && support_force_n_ > off_n_; }
  // In the air after a time on the ground, the support may still carry the
  // filtered N (up to ground_contact_off_n when the contact lets go at
  // F_z > M g - off_n, before the body lifts): the accelerometer then reads
  // a_z = (F_z + N) / M with N unknown in [0, N_f], so its a_z variance
  // gains (N_bound / M)^2 [m^2/s^4], N_bound = max(N_f, 0); while it
  // may_touch the ground below the contact's threshold, N_bound =
  // max(N_f, ground_contact_on_n). 0 until the body was first on the
  // ground (a start in the air is unchanged).
  double ReleasedSupportVarianceM2S4() const;
  // While it may_touch the ground, a touch may hold the body still (a
  // landing gear or skid on the ground stops the pitch): the gyro reads the
  // free body's rate or 0, so its variance gains the predicted rate's square
  // [rad^2/s^2]; 0 otherwise.
  double HeldRateVariance(double predicted_rate_rad_s) const {
    return may_touch() && std::isfinite(predicted_rate_rad_s) ? predicted_rate_rad_s * predicted_rate_rad_s : 0.0;
  }
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
  bool has_been_supported_ = false;
  int64_t supported_utime_ = -1;  // the newest hold of the contact [us]; -1 none
  int64_t released_utime_ = -1;   // the newest let-go of the contact [us]; -1 none
  double may_touch_m_;            // ground_may_touch_m [m]
  int64_t may_touch_after_us_;    // ground_may_touch_after_s [us]
  bool has_ground_height_ = false;
  double ground_height_m_ = 0.0;  // POSE z while the contact last held [m]
  bool near_ground_ = false;      // the newest POSE within may_touch_m_ of it
};

}  // namespace birotor
