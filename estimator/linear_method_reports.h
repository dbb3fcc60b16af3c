// What the two linear methods (LinearForceEstimator, the birotor's, and
// MultiArmLinearEstimator, any described vehicle) share in their fusion
// reports: both fuse in scaled coordinates x = diag(scale) x_s, and both gate
// the strain and the gyro with the EKF's gates.
#pragma once

#include <limits>

#include "estimator/estimator_config.h"
#include "estimator/fusion_report.h"

namespace birotor {

// A report in the measurement's physical unit: y and S scaled back by the
// measurement's scale (the NIS is the same in both).
inline FusionReport LinearReportInPhysicalUnits(FusionReport report, double scale) {
  report.innovation *= scale;
  report.innovation_variance *= scale * scale;
  return report;
}

// The strain's and the gyro's NIS gates (ekf.strain_gate_nis,
// ekf.gyro_gate_nis); NaN for telemetry and the accelerometer (not gated).
inline double LinearMethodGate(const EkfOptions& noise, FusionSource source) {
  if (source == FusionSource::kStrain) return noise.strain_gate_nis;
  if (source == FusionSource::kGyro) return noise.gyro_gate_nis;
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace birotor
