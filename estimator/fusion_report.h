// What one measurement fusion did: the innovation, its covariance, the
// normalised innovation squared (NIS) against that measurement's chi-square
// gate, and the outcome. Every method reports one per measurement it is given
// (as PX4 EKF2 keeps a status per aiding source), returned with the call that
// fused it, so the health message counts what was really fused, per input.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>

#include "samples/multi_arm_samples.h"

namespace birotor {

// The measurements a method can fuse. A new measurement (a gauge offset, a
// harmonic) is appended before kNumFusionSources and mapped to the input
// channel it comes from in fusion_counters.cc (InputChannelOf).
enum class FusionSource : int {
  kStrain = 0,         // arm deflections b1, b2 (b_1 .. b_N) [rad] (STRAIN, STRAIN_N)
  kTelemetry = 1,      // ESC rotor speeds omega1, omega2 (omega_1 .. omega_N) [rad/s] (MOTOR, MOTOR_N)
  kGyro = 2,           // body pitch rate phi_dot [rad/s] (IMU)
  kAccelerometer = 3,  // specific force a_z in free flight [m/s^2] (IMU)
};
constexpr int kNumFusionSources = 4;

enum class FusionOutcome : int {
  kFused = 0,         // the state (and covariance) were updated with it
  kRejectedGate = 1,  // NIS above the gate: not fused
  kNotFused = 2,      // not attempted: older than the filter's time, pushed out
                      // of a full queue, discarded by a re-initialisation, or
                      // not used by the method
};

// Largest measurement dimension of any model: the strain and telemetry of
// the N-arm EKF, one per arm (the birotor's: 2).
constexpr int kMaxMeasurementSize = kMaxSampleArms;

struct FusionReport {
  FusionSource source = FusionSource::kStrain;
  FusionOutcome outcome = FusionOutcome::kNotFused;
  int64_t utime = 0;  // stamp of the measurement; the filter was predicted to it [us]
  int size = 0;       // measurement dimension m (0: no innovation computed)
  // y = z - h(x) and the diagonal of S = H P H^T + R (each component's
  // variance; the gate used all of S), in the measurement's unit and its
  // square (first m entries valid). A component the method did not measure
  // (an N-arm vehicle's arm without a gauge or a reading) has y_j = 0 and
  // variance 0: consumers leave it out.
  Eigen::Matrix<double, kMaxMeasurementSize, 1> innovation = Eigen::Matrix<double, kMaxMeasurementSize, 1>::Zero();
  Eigen::Matrix<double, kMaxMeasurementSize, 1> innovation_variance =
      Eigen::Matrix<double, kMaxMeasurementSize, 1>::Zero();
  // y^T S^-1 y, chi-square with m degrees of freedom; NaN when not computed.
  double nis = std::numeric_limits<double>::quiet_NaN();
  // The threshold nis was compared with; NaN when the method has no gate.
  double gate = std::numeric_limits<double>::quiet_NaN();
  // Fused only after the covariance was inflated, because the gate had
  // rejected this input gate_consecutive_limit times in a row.
  bool fused_after_inflation = false;
};

// A report without an innovation (not fused, or used without a gate).
inline FusionReport MakeFusionReport(FusionSource source, int64_t utime, FusionOutcome outcome) {
  FusionReport report;
  report.source = source;
  report.utime = utime;
  report.outcome = outcome;
  return report;
}

// The reports one call of a method produced, in the order they happened: the
// call's output (the method never calls back into its caller). Fixed
// capacity, no allocation: one strain step of the EKF reports at most its
// queued MOTOR and IMU samples (2 x 128, the IMU with two readings each) and
// the strain sample, 385 in all.
class FusionReports {
 public:
  static constexpr int kCapacity = 512;
  void clear() { size_ = 0; }
  int size() const { return size_; }
  const FusionReport& operator[](int i) const { return reports_[i]; }
  const FusionReport* begin() const { return reports_; }
  const FusionReport* end() const { return reports_ + size_; }
  // Appends; beyond the capacity the report is counted in overflowed() only.
  void Add(const FusionReport& report) {
    if (size_ < kCapacity) {
      reports_[size_++] = report;
    } else {
      ++overflowed_;
    }
  }
  int64_t overflowed() const { return overflowed_; }

 private:
  FusionReport reports_[kCapacity];
  int size_ = 0;
  int64_t overflowed_ = 0;
};

}  // namespace birotor
