#include "estimator/gauge_tare.h"

#include <algorithm>
#include <cmath>

#include "samples/rotor_count.h"

namespace birotor {
namespace {

bool Fresh(int64_t sample_utime, int64_t now_utime, double timeout_s) {
  return sample_utime <= now_utime && static_cast<double>(now_utime - sample_utime) * 1e-6 <= timeout_s;
}

}  // namespace

const char* TareRefusalName(TareRefusal refusal) {
  switch (refusal) {
    case TareRefusal::kNone:
      return "";
    case TareRefusal::kMotorsRunning:
      return "motors_running";
    case TareRefusal::kBodyMoving:
      return "body_moving";
    case TareRefusal::kOutOfRange:
      return "out_of_range";
  }
  return "?";
}

const char* GaugeOffsetSourceName(GaugeOffsetSource source) {
  switch (source) {
    case GaugeOffsetSource::kParameters:
      return "params";
    case GaugeOffsetSource::kTare:
      return "tare";
    case GaugeOffsetSource::kStateFile:
      return "state_file";
  }
  return "?";
}

GaugeTare::GaugeTare(const BirotorParams& params, const TareOptions& options)
    : options_(options), gravity_m_s2_(params.gravity_m_s2) {
  for (int i = 0; i < 2; ++i) rest_reading_rad_[i] = RestReadingRad(params, i);
}

void GaugeTare::AddMotor(const MotorSample& sample) {
  motor_ = sample;
  has_motor_ = true;
}

void GaugeTare::AddImu(const ImuSample& sample) {
  imu_ = sample;
  has_imu_ = true;
}

bool GaugeTare::Resting(int64_t utime, TareRefusal* why_not) const {
  bool stopped = has_motor_ && Fresh(motor_.utime, utime, options_.input_timeout_s);
  for (int i = 0; i < 2 && stopped; ++i) {
    const double meas = motor_.omega_meas_rad_s[i];
    stopped = std::abs(motor_.omega_cmd_rad_s[i]) <= options_.motor_stopped_rad_s &&
              (!std::isfinite(meas) || std::abs(meas) <= options_.motor_stopped_rad_s);
  }
  if (!stopped) {
    *why_not = TareRefusal::kMotorsRunning;
    return false;
  }
  const bool still =
      has_imu_ && Fresh(imu_.utime, utime, options_.input_timeout_s) &&
      std::abs(imu_.gyro_y_rad_s) <= options_.rest_gyro_rad_s &&
      std::abs(std::hypot(imu_.accel_x_m_s2, imu_.accel_z_m_s2) - gravity_m_s2_) <= options_.rest_accel_m_s2;
  if (!still) {
    *why_not = TareRefusal::kBodyMoving;
    return false;
  }
  return true;
}

void GaugeTare::CloseWindow() {
  window_open_ = false;
  window_accepted_ = false;
  count_ = 0;
  for (int i = 0; i < 2; ++i) sum_[i] = sum_sq_[i] = 0;
}

TareEvent GaugeTare::Refuse(TareRefusal reason) {
  switch (reason) {
    case TareRefusal::kMotorsRunning:
      ++counters_.refused_motors_running;
      break;
    case TareRefusal::kBodyMoving:
      ++counters_.refused_body_moving;
      break;
    case TareRefusal::kOutOfRange:
      ++counters_.refused_out_of_range;
      break;
    case TareRefusal::kNone:
      break;
  }
  counters_.last_refusal = reason;
  CloseWindow();
  return TareEvent::kRefused;
}

TareEvent GaugeTare::AddStrain(const StrainSample& reading) {
  if (!options_.enabled) return TareEvent::kNone;
  TareRefusal why_not = TareRefusal::kNone;
  if (!Resting(reading.utime, &why_not)) {
    if (!window_open_) return TareEvent::kNone;
    if (window_accepted_) {  // the rest ended after a tare: it stands
      CloseWindow();
      return TareEvent::kNone;
    }
    return Refuse(why_not);  // the rest ended too early for a tare
  }
  if (!window_open_) {
    window_open_ = true;
    window_start_utime_ = reading.utime;
    next_tare_utime_ = reading.utime + static_cast<int64_t>(std::llround(options_.window_s * 1e6));
  }
  ++count_;
  for (int i = 0; i < 2; ++i) {
    const double d = reading.deflection_rad[i] - rest_reading_rad_[i];
    sum_[i] += d;
    sum_sq_[i] += d * d;
  }
  if (reading.utime < next_tare_utime_ || count_ < 2) return TareEvent::kNone;

  // o_i = mean(b_meas_i) - s_i b_rest_i; one sigma: the mean's standard error
  // (white noise) and the rest deflection's own uncertainty.
  const double n = static_cast<double>(count_);
  double offset[kBirotorRotors], std_rad[2];
  for (int i = 0; i < 2; ++i) {
    offset[i] = sum_[i] / n;
    const double variance = std::max(0.0, (sum_sq_[i] - n * offset[i] * offset[i]) / (n - 1.0));
    std_rad[i] = std::sqrt(variance / n + options_.model_std_rad * options_.model_std_rad);
    if (!(std::abs(offset[i]) <= options_.max_offset_rad)) return Refuse(TareRefusal::kOutOfRange);
  }
  for (int i = 0; i < 2; ++i) {
    offset_rad_[i] = offset[i];
    offset_std_rad_[i] = std_rad[i];
  }
  window_accepted_ = true;
  next_tare_utime_ += static_cast<int64_t>(std::llround(options_.window_s * 1e6));
  ++counters_.accepted;
  return TareEvent::kAccepted;
}

}  // namespace birotor
