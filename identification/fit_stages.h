// The stages every output-error fit of the vehicle parameters shares, bench
// and flight alike: after the solve, one-sigma values of the shared ratio
// blocks (information matrix, inflated, and the cluster sandwich), the
// floors of what the data cannot give better, and the estimate itself.
#pragma once

#include <ceres/problem.h>

#include <string>
#include <vector>

#include "identification/fit_support.h"
#include "identification/identification_options.h"
#include "identification/identification_result.h"

namespace birotor {

// One shared parameter of a fit: a one-scalar ratio block and its unit.
struct RatioParameter {
  ParameterEstimate* estimate;  // where the value, sigma and status go
  double* ratio;                // the Ceres block [1]
  double scale;                 // value = ratio * scale (unit of the key)
  // The size a relative sigma is judged against (0: |value|; the gauge
  // offsets, which may be zero, use the strain noise).
  double judge_size = 0.0;
};

// Solve-with-sigmas stage: one sigma of each block from the information
// matrix inflated by `inflation` (ComputeBlockSigmas); with clusters, the
// larger of that and the cluster sandwich (ComputeClusterRobustSigmas).
// Every block must be in the problem (constant ones get determined = false
// through ComputeBlockSigmas's probe only when free).
std::vector<BlockSigma> SharedSigmas(ceres::Problem* problem, const std::vector<double*>& blocks, double inflation,
                                     const std::vector<ceres::ResidualBlockId>& clusters, int num_threads);

// Result stage: value and sigma in the key's unit, determined when the
// information matrix is regular along it and sigma <= max_relative_sigma of
// its size (RatioParameter::judge_size).
void FillEstimate(const RatioParameter& p, const BlockSigma& sigma, double max_relative_sigma,
                  const EstimateNote& note);

// Floor stage: sigma^2 += (relative value)^2 (no-op for a NaN value or a
// floor of 0); `floor` names it in the note.
void AddRelativeFloor(ParameterEstimate* e, double relative, EstimateRemark floor);

// The bench floors (options.bench_damping_floor on d, bench_frequency_floor
// on k / m_p, given to m_p, or to k when the tip mass is weighed): what the
// 1 kHz load-cell input cannot give better. Shared by the bench arm fit and
// the joint bench + flight fit.
void AddBenchFloors(const IdentificationOptions& options, ParameterEstimate* stiffness, ParameterEstimate* damping,
                    ParameterEstimate* tip_mass);

// The combinations of the free blocks the data determine where the blocks
// themselves are not separated (DescribeCorrelations at |rho| > 0.99).
std::vector<DeterminedCombination> CorrelationLines(ceres::Problem* problem,
                                                    const std::vector<RatioParameter>& parameters, int num_threads);

// Result stage: the determined estimates go into params (by key), all into
// result->estimates in the given order.
void StoreEstimates(const std::vector<ParameterEstimate>& estimates, IdentificationResult* result);

// Writes the value of a `vehicle:` key (the ParameterEstimate keys of
// identification, gauge_scale[i] and gauge_offset_rad[i] included); false
// for a key identification does not fit.
bool SetVehicleValue(const std::string& key, double value, BirotorParams* params);

}  // namespace birotor
