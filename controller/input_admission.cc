#include "controller/input_admission.h"

#include <cmath>

#include "numerics/time_units.h"

namespace birotor {
namespace {

// Plausibility limits of the inputs: beyond them a sample is a corrupt one,
// not a state of this vehicle (dropped and counted as invalid).
constexpr double kMaxPositionM = 1e4;          // |x|, |z| of POSE [m]
constexpr double kMaxAngleRad = 10.0;          // |phi| of POSE [rad]
constexpr double kMaxRateRadS = 100.0;         // |gyro| [rad/s]
constexpr double kMaxSpecificForceM_S2 = 1e3;  // |accel| [m/s^2]

bool Within(double value, double limit) { return std::isfinite(value) && std::fabs(value) <= limit; }

}  // namespace

bool PlausiblePose(const PoseSample& sample) {
  return Within(sample.x_m, kMaxPositionM) && Within(sample.z_m, kMaxPositionM) &&
         Within(sample.phi_rad, kMaxAngleRad) && sample.utime >= 0;
}

bool PlausibleImu(const ImuSample& sample) {
  return Within(sample.gyro_y_rad_s, kMaxRateRadS) && Within(sample.accel_x_m_s2, kMaxSpecificForceM_S2) &&
         Within(sample.accel_z_m_s2, kMaxSpecificForceM_S2) && sample.utime >= 0;
}

bool AdmitToStream(const SupervisionParams& s, const StreamMessage& message, bool valid, int64_t now_us,
                   SeqStreamLock* lock, ControllerInputCounters* counters) {
  ++counters->received;
  if (!valid) {
    ++counters->rejected_invalid;
    return false;
  }
  const double age_s = ElapsedSeconds(now_us, message.utime);
  if (-age_s > s.clock_future_window_s) {
    ++counters->rejected_future;
    return false;
  }
  if (age_s > s.clock_past_window_s) {
    ++counters->rejected_past;
    return false;
  }
  if (lock == nullptr) return true;
  switch (lock->Admit(message.seq, message.utime, message.digest, now_us)) {
    case SeqStreamLock::Verdict::kLocked:
    case SeqStreamLock::Verdict::kInStream:
      return true;
    case SeqStreamLock::Verdict::kDuplicate:
      ++counters->rejected_out_of_order;
      return false;
    case SeqStreamLock::Verdict::kForeign:
    case SeqStreamLock::Verdict::kHeld:
      ++counters->rejected_foreign;
      return false;
  }
  return false;
}

bool AcceptNewest(int64_t utime, ControllerInputCounters* counters) {
  if (counters->last_utime >= 0 && utime <= counters->last_utime) {
    ++counters->rejected_out_of_order;
    return false;
  }
  ++counters->accepted;
  counters->last_utime = utime;
  return true;
}

SeqStreamLockParams StreamLockParams(const SupervisionParams& s, double max_rate_hz) {
  SeqStreamLockParams params;
  params.max_rate_hz = max_rate_hz;
  params.rate_margin = s.stream_rate_margin;
  params.seq_slack = s.stream_seq_slack;
  params.stamp_slack_s = s.stream_stamp_slack_s;
  params.silence_s = s.stream_silence_s;
  params.conflict_hold_s = s.conflict_hold_s;
  return params;
}

void ForceRecovery::OnAccepted(int64_t utime, int64_t previous_utime, bool valid) {
  newest_healthy_ = valid;
  if (!valid) {
    healthy_since_us_ = -1;
    return;
  }
  const bool on_time = previous_utime >= 0 && ElapsedSeconds(utime, previous_utime) <= timeout_s_;
  if (healthy_since_us_ < 0 || !on_time) healthy_since_us_ = utime;
}

bool ForceRecovery::Usable(int64_t now_us, int64_t newest_utime) const {
  // Age of a stamp at now_us: a stamp ahead of the clock is not usable.
  const auto within = [now_us](int64_t stamp_us, double window_s) {
    return stamp_us >= 0 && now_us >= stamp_us && ElapsedSeconds(now_us, stamp_us) <= window_s;
  };
  const bool recovered =
      healthy_since_us_ >= 0 && now_us >= healthy_since_us_ && ElapsedSeconds(now_us, healthy_since_us_) >= recovery_s_;
  return newest_healthy_ && within(newest_utime, timeout_s_) && recovered;
}

}  // namespace birotor
