// The bench logs' residual blocks in a joint bench + flight fit (one Ceres
// problem over the shared vehicle parameters, flight_identification.cc):
// load-cell thrust pairs on c_T and clamped-arm windows on k, d, m_p.
#pragma once

#include <ceres/problem.h>

#include <array>
#include <deque>
#include <vector>

#include "identification/identification_options.h"
#include "model/birotor_params.h"
#include "samples/sensor_log.h"

namespace birotor {

// Shared parameter blocks, each a ratio to the bench fit's value (the
// scales of both the bench residuals and the flight residuals).
struct SharedRatioBlocks {
  double* stiffness;
  double* damping;
  double* thrust_coeff;
  double* tip_mass;
};

// Storage of the bench-only blocks; must not move once added to a problem.
struct BenchResiduals {
  std::vector<ceres::ResidualBlockId> thrust;  // one per load-cell/telemetry pair
  std::vector<ceres::ResidualBlockId> arms;    // one per clamped-arm window
  std::deque<std::array<double, 2>> states;    // per arm window: (b_0 [rad], b_dot_0 [rad/s])
  // Gauge scale s_i and offset o_i / sigma_b, held at the bench fit's values:
  // the flight reads its deflections through them, so they stay the bench's.
  std::array<double, 2> gauge_scale = {1.0, 1.0};
  std::array<double, 2> offset_ratio = {0.0, 0.0};
};

// Adds the residuals of the bench logs. `bench` is the bench logs' own fit
// (IdentifyBenchThrust, IdentifyBenchArms): its c_T, k, d, m_p are the ratio
// scales, its gauge calibration is held. A weighed tip mass
// (options.calibration) adds its prior on m_p, or holds m_p when its sigma is 0.
void AddBenchResiduals(const std::vector<SensorLog>& logs, const BirotorParams& bench,
                       const IdentificationOptions& options, ceres::Problem* problem, const SharedRatioBlocks& shared,
                       BenchResiduals* out);

// RMS of load-cell force - c_T omega^2 over every paired sample of the logs
// [N] (not whitened: the sigma differs per sample).
double ThrustResidualRmsN(const std::vector<SensorLog>& logs, double thrust_coeff_n_s2_rad2);

}  // namespace birotor
