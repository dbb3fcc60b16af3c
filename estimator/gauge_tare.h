// The tare of the strain gauges: while the motors are stopped and the body is
// at rest on the ground, gauge i reads s_i b_rest_i + o_i + noise with the
// known rest deflection b_rest_i = -/+ m_p g L / k (gauge_calibration.h), so
// the mean reading gives the zero offset o_i.
//
// The rule (every threshold in TareOptions):
//  - motors stopped: the newest MOTOR sample, not older than input_timeout_s,
//    has both commands and both finite telemetry readings <= motor_stopped_rad_s;
//  - body at rest: the newest IMU sample, not older than input_timeout_s, has
//    |gyro_y| <= rest_gyro_rad_s and ||accel| - g| <= rest_accel_m_s2.
// While both hold, strain readings accumulate. After window_s of rest the tare
// is made, and refined every further window_s from all readings of the rest;
// a mean offset with |o_i| > max_offset_rad is refused (reading outside the
// physical range) and the window restarts. A rest that ends before window_s
// (motors started, body moved) is refused with that reason. Refusals are
// counted and never change the offset. No allocation per sample.
#pragma once

#include <cstdint>

#include "estimator/estimator_config.h"
#include "estimator/gauge_calibration.h"
#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

enum class TareRefusal : int { kNone = 0, kMotorsRunning = 1, kBodyMoving = 2, kOutOfRange = 3 };
const char* TareRefusalName(TareRefusal refusal);  // "", "motors_running", "body_moving", "out_of_range"

// What one strain reading did to the tare.
enum class TareEvent { kNone, kAccepted, kRefused };

struct TareCounters {
  int64_t accepted = 0;  // tares made (a long rest refines: each refinement counts)
  int64_t refused_motors_running = 0;
  int64_t refused_body_moving = 0;
  int64_t refused_out_of_range = 0;
  TareRefusal last_refusal = TareRefusal::kNone;
};

class GaugeTare {
 public:
  GaugeTare(const BirotorParams& params, const TareOptions& options);

  void AddMotor(const MotorSample& sample);
  void AddImu(const ImuSample& sample);
  // One raw (uncalibrated) strain reading, finite. On kAccepted the new
  // offsets are in offset_rad() / offset_std_rad().
  TareEvent AddStrain(const StrainSample& reading);

  const double* offset_rad() const { return offset_rad_; }          // o_i of the newest tare [rad]
  const double* offset_std_rad() const { return offset_std_rad_; }  // one sigma [rad]
  const TareCounters& counters() const { return counters_; }
  // Motors stopped and body at rest at utime (the rule above).
  bool Resting(int64_t utime, TareRefusal* why_not) const;

 private:
  TareEvent Refuse(TareRefusal reason);
  void CloseWindow();

  TareOptions options_;
  double gravity_m_s2_;
  double rest_reading_rad_[2];  // s_i b_rest_i [rad]
  bool has_motor_ = false, has_imu_ = false;
  MotorSample motor_;
  ImuSample imu_;

  // Current rest window: sums of (reading - rest reading) per gauge.
  bool window_open_ = false;
  bool window_accepted_ = false;  // a tare was made from this rest
  int64_t window_start_utime_ = 0;
  int64_t next_tare_utime_ = 0;
  int64_t count_ = 0;
  double sum_[2] = {0, 0}, sum_sq_[2] = {0, 0};

  double offset_rad_[kBirotorRotors] = {0, 0};
  double offset_std_rad_[kBirotorRotors] = {0, 0};
  TareCounters counters_;
};

}  // namespace birotor
