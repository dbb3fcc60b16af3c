// The gauge offsets' departure from their anchor along the common-force direction.
#include "estimator/offset_departure.h"

#include <algorithm>
#include <cmath>

namespace birotor {

OffsetDepartureTest::OffsetDepartureTest(double limit_sigma, double hold_s, int arms, const double* direction,
                                         const double* drift_psd_rad2_s)
    : limit_sigma_(limit_sigma),
      hold_us_(static_cast<int64_t>(std::llround(hold_s * 1e6))),
      arms_(std::clamp(arms, 1, kMaxSampleArms)) {
  for (int i = 0; i < arms_; ++i) {
    direction_[i] = std::isfinite(direction[i]) ? direction[i] : 0.0;
    drift_psd_rad2_s_[i] = std::max(drift_psd_rad2_s[i], 0.0);
  }
}

void OffsetDepartureTest::Anchor(const double* offset_rad, const double* offset_std_rad) {
  for (int i = 0; i < arms_; ++i) {
    anchor_rad_[i] = offset_rad[i];
    anchor_variance_rad2_[i] = offset_std_rad[i] * offset_std_rad[i];
  }
  anchor_utime_ = -1;
  beyond_since_utime_ = -1;
  state_ = OffsetDepartureState();
  for (int i = 0; i < arms_; ++i) {
    state_.anchor_rad[i] = offset_rad[i];
    state_.anchor_std_rad[i] = offset_std_rad[i];
  }
}

bool OffsetDepartureTest::Add(int64_t utime, const double* offset_rad, bool free_flight, bool near_ground) {
  if (!enabled()) return false;
  if (anchor_utime_ < 0 || utime < anchor_utime_) anchor_utime_ = utime;
  if (!free_flight) {
    beyond_since_utime_ = -1;
    state_.statistic = 0;
    return false;
  }
  // z = sum_i w_i (o_i - a_i) / sqrt(sum_i w_i^2 (s_a,i^2 + q_i (t - t_a))).
  const double elapsed_s = (utime - anchor_utime_) * 1e-6;
  double departure_rad = 0, variance_rad2 = 0, direction_norm2 = 0;
  for (int i = 0; i < arms_; ++i) {
    const double w = direction_[i];
    departure_rad += w * (offset_rad[i] - anchor_rad_[i]);
    variance_rad2 += w * w * (anchor_variance_rad2_[i] + drift_psd_rad2_s_[i] * elapsed_s);
    direction_norm2 += w * w;
  }
  if (!(variance_rad2 > 0) || !std::isfinite(departure_rad)) return false;
  state_.z = departure_rad / std::sqrt(variance_rad2);
  state_.common_multiple = departure_rad / direction_norm2;
  state_.arm_z = 0;
  state_.arm = -1;
  if (near_ground) JudgeEachGauge(offset_rad, elapsed_s);
  state_.statistic = std::max(std::fabs(state_.z), state_.arm_z) / limit_sigma_;
  state_.peak_abs_z = std::max(state_.peak_abs_z, std::fabs(state_.z));
  if (state_.departed) return false;
  if (state_.statistic <= 1.0) {
    beyond_since_utime_ = -1;
    return false;
  }
  if (beyond_since_utime_ < 0) beyond_since_utime_ = utime;
  if (utime - beyond_since_utime_ < hold_us_) return false;
  state_.departed = true;
  state_.departed_utime = utime;
  state_.departed_arm = state_.arm_z > std::fabs(state_.z) ? state_.arm : -1;
  return true;
}

void OffsetDepartureTest::JudgeEachGauge(const double* offset_rad, double elapsed_s) {
  // z_i = (o_i - a_i) / sqrt(s_a,i^2 + q_i (t - t_a)); a gauge without a
  // prior (none on that arm) is not judged.
  for (int i = 0; i < arms_; ++i) {
    const double variance_rad2 = anchor_variance_rad2_[i] + drift_psd_rad2_s_[i] * elapsed_s;
    const double departure_rad = offset_rad[i] - anchor_rad_[i];
    if (!(variance_rad2 > 0) || !std::isfinite(departure_rad)) continue;
    const double z = std::fabs(departure_rad) / std::sqrt(variance_rad2);
    if (z > state_.arm_z) {
      state_.arm_z = z;
      state_.arm = i;
    }
  }
}

}  // namespace birotor
