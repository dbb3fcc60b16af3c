// Best available rotor speeds for the baseline estimators: ESC telemetry when
// it is finite and recent, else the first-order motor model driven by the
// commands, omega_dot = (clamp(omega_cmd) - omega) / tau_m.
#pragma once

#include <cstdint>

#include "model/birotor_params.h"
#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

class MotorSpeedTracker {
 public:
  // Telemetry older than telemetry_timeout_s is not used [s].
  explicit MotorSpeedTracker(const BirotorParams& params, double telemetry_timeout_s = 0.05)
      : params_(params), telemetry_timeout_s_(telemetry_timeout_s) {}

  void Reset();
  void AddMotor(const MotorSample& sample);
  // Advances the motor model to utime (exact exponential step over the held
  // command) and selects the speed of each rotor.
  void Advance(int64_t utime);

  bool has_motor() const { return has_motor_; }
  double omega_rad_s(int rotor) const { return omega_rad_s_[rotor]; }
  bool from_telemetry(int rotor) const { return from_telemetry_[rotor]; }
  // Thrust efficiency of an estimated force against the nominal map,
  // force_n / (c_T omega_i^2) [1]; 1 without motor input or below 1 uN nominal.
  double ThrustScale(int rotor, double force_n) const {
    const double nominal = params_.thrust_coeff_n_s2_rad2 * omega_rad_s_[rotor] * omega_rad_s_[rotor];
    return (has_motor_ && nominal > 1e-6) ? force_n / nominal : 1.0;
  }

 private:
  BirotorParams params_;
  double telemetry_timeout_s_;
  bool has_motor_ = false;
  int64_t model_utime_ = 0;
  double command_rad_s_[kBirotorRotors] = {0, 0};  // clamped command in effect
  double model_rad_s_[2] = {0, 0};                 // motor-model speed at model_utime_
  double telemetry_rad_s_[2] = {0, 0};
  int64_t telemetry_utime_[2] = {-1, -1};
  double omega_rad_s_[kBirotorRotors] = {0, 0};
  bool from_telemetry_[2] = {false, false};
};

}  // namespace birotor
