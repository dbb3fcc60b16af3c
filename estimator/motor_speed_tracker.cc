#include "estimator/motor_speed_tracker.h"

#include <cmath>

#include "model/plant.h"
#include "samples/rotor_count.h"

namespace birotor {

void MotorSpeedTracker::Reset() {
  has_motor_ = false;
  for (int i = 0; i < kBirotorRotors; ++i) {
    telemetry_utime_[i] = -1;
    from_telemetry_[i] = false;
    omega_rad_s_[i] = 0;
  }
}

void MotorSpeedTracker::AddMotor(const MotorSample& sample) {
  if (!has_motor_) {
    // Start the model at the telemetry if there is one, else at the command.
    for (int i = 0; i < kBirotorRotors; ++i) {
      const double meas = sample.omega_meas_rad_s[i];
      model_rad_s_[i] = std::isfinite(meas) ? meas : ClampCommand(params_, sample.omega_cmd_rad_s[i]);
    }
    model_utime_ = sample.utime;
    has_motor_ = true;
  } else {
    Advance(sample.utime);
  }
  for (int i = 0; i < kBirotorRotors; ++i) {
    command_rad_s_[i] = ClampCommand(params_, sample.omega_cmd_rad_s[i]);
    if (std::isfinite(sample.omega_meas_rad_s[i])) {
      telemetry_rad_s_[i] = sample.omega_meas_rad_s[i];
      telemetry_utime_[i] = sample.utime;
    }
  }
}

void MotorSpeedTracker::Advance(int64_t utime) {
  if (!has_motor_) return;
  if (utime > model_utime_) {
    const double dt_s = static_cast<double>(utime - model_utime_) * 1e-6;
    for (int i = 0; i < kBirotorRotors; ++i) {
      model_rad_s_[i] = MotorStep(model_rad_s_[i], command_rad_s_[i], params_.motor_time_constant_s, dt_s);
    }
    model_utime_ = utime;
  }
  for (int i = 0; i < kBirotorRotors; ++i) {
    from_telemetry_[i] = telemetry_utime_[i] >= 0 && (utime - telemetry_utime_[i]) * 1e-6 <= telemetry_timeout_s_;
    omega_rad_s_[i] = from_telemetry_[i] ? telemetry_rad_s_[i] : model_rad_s_[i];
  }
}

}  // namespace birotor
