// Bad-sample removal for identification logs.
#include "identification/sample_cleaning.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace birotor {
namespace {

// 2^53 us (285 years): the stamps the estimator pipeline accepts too.
constexpr int64_t kMaxUtime = int64_t{1} << 53;

// Copies of one sample looked past when checking that a forward jump is confirmed.
constexpr size_t kMaxDuplicatesSkipped = 8;

bool StampInRange(int64_t utime) { return utime >= 0 && utime < kMaxUtime; }

bool Finite(const StrainSample& s) { return std::isfinite(s.deflection_rad[0]) && std::isfinite(s.deflection_rad[1]); }
bool Finite(const MotorSample& s) {
  // NaN telemetry means "no reading" and is handled by the fits; Inf is corrupt.
  return std::isfinite(s.omega_cmd_rad_s[0]) && std::isfinite(s.omega_cmd_rad_s[1]) &&
         !std::isinf(s.omega_meas_rad_s[0]) && !std::isinf(s.omega_meas_rad_s[1]);
}
bool Finite(const ImuSample& s) {
  return std::isfinite(s.gyro_y_rad_s) && std::isfinite(s.accel_x_m_s2) && std::isfinite(s.accel_z_m_s2);
}
bool Finite(const PoseSample& s) { return std::isfinite(s.x_m) && std::isfinite(s.z_m) && std::isfinite(s.phi_rad); }
bool Finite(const LoadCellSample& s) { return std::isfinite(s.force_n[0]) && std::isfinite(s.force_n[1]); }

template <class Sample>
DroppedSamples CleanStream(std::vector<Sample>* samples, int64_t max_forward_jump_us) {
  DroppedSamples dropped;
  std::vector<Sample> kept;
  kept.reserve(samples->size());
  const size_t count = samples->size();
  for (size_t i = 0; i < count; ++i) {
    const Sample& sample = (*samples)[i];
    if (!StampInRange(sample.utime)) {
      ++dropped.bad_stamp;
      continue;
    }
    if (!Finite(sample)) {
      ++dropped.non_finite;
      continue;
    }
    if (!kept.empty() && sample.utime == kept.back().utime) {
      ++dropped.duplicate;
      continue;
    }
    if (!kept.empty() && sample.utime < kept.back().utime) {
      ++dropped.out_of_order;
      continue;
    }
    // Differences of stamps in [0, 2^53) cannot overflow.
    const bool jumps = kept.empty() || sample.utime - kept.back().utime > max_forward_jump_us;
    // The confirming sample is the next one with another stamp (duplicates of
    // this one are skipped; a few at most, so the scan is bounded).
    size_t next_index = i + 1;
    while (next_index < count && next_index - i <= kMaxDuplicatesSkipped &&
           (*samples)[next_index].utime == sample.utime) {
      ++next_index;
    }
    if (jumps && next_index < count) {
      const int64_t next = (*samples)[next_index].utime;
      const bool confirmed = StampInRange(next) && next > sample.utime && next - sample.utime <= max_forward_jump_us;
      if (!confirmed) {
        ++dropped.bad_stamp;
        continue;
      }
    }
    kept.push_back(sample);
  }
  samples->swap(kept);
  return dropped;
}

}  // namespace

DroppedSamples& DroppedSamples::operator+=(const DroppedSamples& other) {
  non_finite += other.non_finite;
  bad_stamp += other.bad_stamp;
  out_of_order += other.out_of_order;
  duplicate += other.duplicate;
  return *this;
}

int64_t SampleCleaningReport::total() const {
  return strain.total() + motor.total() + imu.total() + pose.total() + loadcell.total();
}

SampleCleaningReport& SampleCleaningReport::operator+=(const SampleCleaningReport& other) {
  strain += other.strain;
  motor += other.motor;
  imu += other.imu;
  pose += other.pose;
  loadcell += other.loadcell;
  return *this;
}

SampleCleaningReport CleanLog(SensorLog* log, int64_t max_forward_jump_us) {
  SampleCleaningReport report;
  report.strain = CleanStream(&log->strain, max_forward_jump_us);
  report.motor = CleanStream(&log->motor, max_forward_jump_us);
  report.imu = CleanStream(&log->imu, max_forward_jump_us);
  report.pose = CleanStream(&log->pose, max_forward_jump_us);
  report.loadcell = CleanStream(&log->loadcell, max_forward_jump_us);
  std::stable_sort(log->truth.begin(), log->truth.end(),
                   [](const TruthSample& a, const TruthSample& b) { return a.utime < b.utime; });
  return report;
}

}  // namespace birotor
