#include "controller/pose_gate.h"

#include <cmath>

#include "numerics/time_units.h"

namespace birotor {
namespace {

// Longest interval between two POSEs of one consistent run [s]: a gap ends
// the run (100 Hz POSE: 10 ms).
constexpr double kMaxRunIntervalS = 0.1;

}  // namespace

bool PoseGate::ContinuesRun(const PoseSample& sample, const BodyState& observer) const {
  if (run_ == 0) return false;
  const double dt_s = ElapsedSeconds(sample.utime, previous_.utime);
  if (!(dt_s > 0.0 && dt_s <= kMaxRunIntervalS)) return false;
  // The previous POSE moved on by the IMU-propagated velocity and pitch rate.
  const Eigen::Vector2d predicted_m = Eigen::Vector2d(previous_.x_m, previous_.z_m) + dt_s * observer.velocity_m_s;
  const double predicted_phi_rad = previous_.phi_rad + dt_s * observer.phi_dot_rad_s;
  return (Eigen::Vector2d(sample.x_m, sample.z_m) - predicted_m).norm() <= params_.pose_reacquire_position_m &&
         std::fabs(sample.phi_rad - predicted_phi_rad) <= params_.pose_reacquire_angle_rad;
}

PoseGate::Verdict PoseGate::Check(const PoseSample& sample, const BodyState& observer, int64_t now_us) {
  const bool inside =
      (Eigen::Vector2d(sample.x_m, sample.z_m) - observer.position_m).norm() <= params_.pose_gate_position_m &&
      std::fabs(sample.phi_rad - observer.phi_rad) <= params_.pose_gate_angle_rad;
  if (inside) {
    gated_since_us_ = -1;
    run_ = 0;
    return Verdict::kInside;
  }
  run_ = ContinuesRun(sample, observer) ? run_ + 1 : 1;
  previous_ = sample;
  if (gated_since_us_ < 0) gated_since_us_ = now_us;
  const bool reset = ElapsedSeconds(now_us, gated_since_us_) >= params_.pose_gate_reset_s;
  const bool reacquired = run_ >= params_.pose_reacquire_count;
  if (!reset && !reacquired) return Verdict::kRefused;
  gated_since_us_ = -1;
  run_ = 0;
  return reacquired ? Verdict::kReacquired : Verdict::kReset;
}

bool MoveObserverOnto(PoseGate::Verdict verdict, const PoseSample& sample, BodyStateObserver* observer) {
  if (verdict != PoseGate::Verdict::kReset && verdict != PoseGate::Verdict::kReacquired) return false;
  const Eigen::Vector2d position_m(sample.x_m, sample.z_m);
  if (verdict == PoseGate::Verdict::kReset) {
    observer->Initialize(position_m, sample.phi_rad);
  } else {
    observer->Relocate(position_m, sample.phi_rad);
  }
  observer->PoseUsedAt(sample.utime);
  return true;
}

}  // namespace birotor
