#include "estimator/ground_contact.h"

#include <algorithm>
#include <cmath>

namespace birotor {

GroundContact::GroundContact(double total_mass_kg, double gravity_m_s2, const EkfOptions& options)
    : total_mass_kg_(total_mass_kg),
      on_n_(options.ground_contact_on_n),
      off_n_(options.ground_contact_off_n),
      filter_s_(options.ground_contact_filter_s),
      support_noise_n_(total_mass_kg * options.accel_noise_m_s2),
      weight_n_(total_mass_kg * gravity_m_s2),
      may_touch_m_(options.ground_may_touch_m),
      may_touch_after_us_(static_cast<int64_t>(std::llround(options.ground_may_touch_after_s * 1e6))) {}

double GroundContact::TimeConstantS(double dt_s) const {
  // A first-order low-pass of white noise of sigma M sigma_a sampled every dt
  // has sigma M sigma_a sqrt(dt / (2 tau)) (tau >> dt). Keep it at a sixth
  // of the hysteresis band, so a noisy accelerometer cannot flip the contact:
  //   tau >= dt (6 M sigma_a / (on - off))^2 / 2.
  const double band_n = on_n_ - off_n_;
  if (!(band_n > 0.0)) return filter_s_;  // no hysteresis: nothing to protect
  const double ratio = 6.0 * support_noise_n_ / band_n;
  return std::max(filter_s_, 0.5 * dt_s * ratio * ratio);
}

void GroundContact::Reset() {
  has_sample_ = false;
  support_force_n_ = 0;
  supported_ = false;
  has_been_supported_ = false;
  supported_utime_ = -1;
  released_utime_ = -1;
  has_ground_height_ = false;
  near_ground_ = false;
}

void GroundContact::OnPose(double z_m) {
  // A rest, not a flicker (one noisy first sample can hold the contact for
  // tens of milliseconds in the air).
  if (supported_ && last_utime_ - supported_utime_ >= may_touch_after_us_) {
    ground_height_m_ = z_m;
    has_ground_height_ = true;
  }
  near_ground_ = has_ground_height_ && may_touch_m_ > 0.0 && z_m - ground_height_m_ < may_touch_m_;
}

bool GroundContact::may_touch() const {
  return near_ground() && released_utime_ >= 0 && last_utime_ - released_utime_ >= may_touch_after_us_;
}

double GroundContact::ReleasedSupportVarianceM2S4() const {
  if (!has_been_supported_) return 0.0;
  const double bound_n = may_touch() ? std::max(support_force_n_, on_n_) : std::max(support_force_n_, 0.0);
  const double a = bound_n / total_mass_kg_;
  return a * a;
}

void GroundContact::Update(int64_t utime, double accel_z_m_s2, double thrust_z_n) {
  if (!std::isfinite(accel_z_m_s2) || !std::isfinite(thrust_z_n)) return;
  // One sample moves the filtered N by at most its weight's share: a spike
  // (a 1e6 m/s^2 reading) must not put a flying vehicle on the ground.
  const double support_n = std::clamp(total_mass_kg_ * accel_z_m_s2 - thrust_z_n, -weight_n_, weight_n_);
  if (!has_sample_) {
    // The filter starts from the air (N_f = 0, not supported) and the next
    // samples move it: one noisy first reading (a 1 m/s^2 accelerometer: N's
    // sigma M sigma_a = 4.6 N) held the contact 38 ms in the air.
    support_force_n_ = 0.0;
  } else if (utime > last_utime_) {
    // Exact discretisation of N_f_dot = (N - N_f) / tau over the sample interval.
    const double dt_s = static_cast<double>(utime - last_utime_) * 1e-6;
    const double alpha = 1.0 - std::exp(-dt_s / TimeConstantS(dt_s));
    support_force_n_ += alpha * (support_n - support_force_n_);
  }
  has_sample_ = true;
  last_utime_ = utime;
  if (support_force_n_ > on_n_) {
    if (!supported_) supported_utime_ = utime;
    supported_ = true;
  } else if (support_force_n_ < off_n_) {
    if (supported_) released_utime_ = utime;
    supported_ = false;
  }
  has_been_supported_ = has_been_supported_ || supported_;
}

}  // namespace birotor
