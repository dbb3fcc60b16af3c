// Best available rotor speeds of an N-rotor vehicle for the N-arm methods
// without speed states (the linear KF, the observer, the inversion): the
// rules of MotorSpeedTracker (estimator/motor_speed_tracker.h) per rotor with
// each rotor's own c_T,i and tau_m,i: ESC telemetry when finite and recent,
// else the first-order motor model driven by the commands.
#pragma once

#include <array>
#include <cstdint>

#include "model/vehicle_description.h"
#include "samples/multi_arm_samples.h"

namespace birotor {

class MultiArmSpeedTracker {
 public:
  // Telemetry older than telemetry_timeout_s is not used [s].
  explicit MultiArmSpeedTracker(const VehicleDescription& vehicle, double telemetry_timeout_s = 0.05);

  void Reset();
  // A sample of another rotor count is not this vehicle's: ignored. Returns
  // whether the sample is this vehicle's with telemetry on every rotor (the
  // methods report such a sample's telemetry as fused).
  bool AddMotor(const MultiArmMotorSample& sample);
  // Advances the motor model to utime (exact step over the held command,
  // model/plant.h MotorStep) and selects the speed of each rotor.
  void Advance(int64_t utime);

  bool has_motor() const { return has_motor_; }
  double omega_rad_s(int rotor) const { return omega_rad_s_[static_cast<size_t>(rotor)]; }
  // c_T,i omega_i^2 [N]; 0 before any motor input.
  double NominalForceN(int rotor) const;
  // Thrust efficiency of an estimated force against the nominal map,
  // force_n / (c_T,i omega_i^2) [1]; 1 without motor input or below 1 uN nominal.
  double ThrustScale(int rotor, double force_n) const;

 private:
  using Values = std::array<double, kMaxArms>;

  int n_;
  double omega_max_rad_s_;
  double telemetry_timeout_s_;
  Values thrust_coeff_{};   // c_T,i [N s^2/rad^2]
  Values time_constant_{};  // tau_m,i [s]
  bool has_motor_ = false;
  int64_t model_utime_ = 0;
  Values command_rad_s_{};  // clamped command in effect
  Values model_rad_s_{};    // motor-model speed at model_utime_
  Values telemetry_rad_s_{};
  std::array<int64_t, kMaxArms> telemetry_utime_{};
  Values omega_rad_s_{};
};

}  // namespace birotor
