#include "estimator/multi_arm_linear_speed.h"

#include <cmath>

#include "model/plant.h"

namespace birotor {

MultiArmSpeedTracker::MultiArmSpeedTracker(const VehicleDescription& vehicle, double telemetry_timeout_s)
    : n_(vehicle.arm_count), omega_max_rad_s_(vehicle.omega_max_rad_s), telemetry_timeout_s_(telemetry_timeout_s) {
  for (int i = 0; i < n_ && i < kMaxArms; ++i) {
    const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
    thrust_coeff_[static_cast<size_t>(i)] = arm.thrust_coeff_n_s2_rad2;
    time_constant_[static_cast<size_t>(i)] = arm.motor_time_constant_s;
  }
  Reset();
}

void MultiArmSpeedTracker::Reset() {
  has_motor_ = false;
  telemetry_utime_.fill(-1);
  omega_rad_s_.fill(0.0);
}

bool MultiArmSpeedTracker::AddMotor(const MultiArmMotorSample& sample) {
  if (sample.n_rotors != n_) return false;
  if (!has_motor_) {
    // Start the model at the telemetry if there is one, else at the command.
    for (size_t i = 0; i < static_cast<size_t>(n_); ++i) {
      const double meas = sample.omega_meas_rad_s[i];
      model_rad_s_[i] = std::isfinite(meas) ? meas : ClampCommand(omega_max_rad_s_, sample.omega_cmd_rad_s[i]);
    }
    model_utime_ = sample.utime;
    has_motor_ = true;
  } else {
    Advance(sample.utime);
  }
  bool every_rotor_measured = true;
  for (size_t i = 0; i < static_cast<size_t>(n_); ++i) {
    command_rad_s_[i] = ClampCommand(omega_max_rad_s_, sample.omega_cmd_rad_s[i]);
    if (std::isfinite(sample.omega_meas_rad_s[i])) {
      telemetry_rad_s_[i] = sample.omega_meas_rad_s[i];
      telemetry_utime_[i] = sample.utime;
    } else {
      every_rotor_measured = false;
    }
  }
  return every_rotor_measured;
}

void MultiArmSpeedTracker::Advance(int64_t utime) {
  if (!has_motor_) return;
  if (utime > model_utime_) {
    const double dt_s = static_cast<double>(utime - model_utime_) * 1e-6;
    for (size_t i = 0; i < static_cast<size_t>(n_); ++i) {
      model_rad_s_[i] = MotorStep(model_rad_s_[i], command_rad_s_[i], time_constant_[i], dt_s);
    }
    model_utime_ = utime;
  }
  for (size_t i = 0; i < static_cast<size_t>(n_); ++i) {
    const bool recent =
        telemetry_utime_[i] >= 0 && static_cast<double>(utime - telemetry_utime_[i]) * 1e-6 <= telemetry_timeout_s_;
    omega_rad_s_[i] = recent ? telemetry_rad_s_[i] : model_rad_s_[i];
  }
}

double MultiArmSpeedTracker::NominalForceN(int rotor) const {
  const size_t k = static_cast<size_t>(rotor);
  return has_motor_ ? thrust_coeff_[k] * omega_rad_s_[k] * omega_rad_s_[k] : 0.0;
}

double MultiArmSpeedTracker::ThrustScale(int rotor, double force_n) const {
  const double nominal = NominalForceN(rotor);
  return (has_motor_ && nominal > 1e-6) ? force_n / nominal : 1.0;
}

}  // namespace birotor
