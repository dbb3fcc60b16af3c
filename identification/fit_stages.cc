#include "identification/fit_stages.h"

#include <algorithm>
#include <cmath>

namespace birotor {

std::vector<BlockSigma> SharedSigmas(ceres::Problem* problem, const std::vector<double*>& blocks, double inflation,
                                     const std::vector<ceres::ResidualBlockId>& clusters, int num_threads) {
  Eigen::MatrixXd covariance;
  std::vector<BlockSigma> sigma =
      ComputeBlockSigmas(problem, blocks, inflation, num_threads, clusters.empty() ? nullptr : &covariance);
  if (clusters.empty()) return sigma;
  const std::vector<double> robust = ComputeClusterRobustSigmas(problem, blocks, covariance, clusters, num_threads);
  for (size_t i = 0; i < robust.size(); ++i) sigma[i].sigma = std::max(sigma[i].sigma, robust[i]);
  return sigma;
}

void FillEstimate(const RatioParameter& p, const BlockSigma& sigma, double max_relative_sigma,
                  const EstimateNote& note) {
  ParameterEstimate* e = p.estimate;
  e->value = *p.ratio * p.scale;
  e->sigma = sigma.sigma * p.scale;
  const double size = p.judge_size > 0.0 ? p.judge_size : std::abs(e->value);
  e->determined = SigmaDetermines(sigma.determined, size, e->sigma, max_relative_sigma);
  e->note = note;
  if (p.judge_size > 0.0) e->note.judged_size = p.judge_size;
}

void AddRelativeFloor(ParameterEstimate* e, double relative, EstimateRemark floor) {
  if (!std::isfinite(e->value) || relative <= 0.0) return;
  e->sigma = std::hypot(e->sigma, relative * e->value);
  e->note.remarks.push_back(floor);
}

void AddBenchFloors(const IdentificationOptions& options, ParameterEstimate* stiffness, ParameterEstimate* damping,
                    ParameterEstimate* tip_mass) {
  AddRelativeFloor(damping, options.bench_damping_floor, EstimateRemark::kDampingFloor);
  ParameterEstimate* floored = options.calibration.TipMassWeighed() ? stiffness : tip_mass;
  AddRelativeFloor(floored, options.bench_frequency_floor, EstimateRemark::kFrequencyFloor);
}

std::vector<DeterminedCombination> CorrelationLines(ceres::Problem* problem,
                                                    const std::vector<RatioParameter>& parameters, int num_threads) {
  std::vector<double*> blocks;
  std::vector<std::string> names;
  std::vector<double> values, sigmas;
  for (const RatioParameter& p : parameters) {
    blocks.push_back(p.ratio);
    names.push_back(p.estimate->symbol);
    values.push_back(p.estimate->value);
    sigmas.push_back(p.estimate->sigma);
  }
  return DescribeCorrelations(ComputeBlockCorrelations(problem, blocks, num_threads), names, values, sigmas, 0.99);
}

bool SetVehicleValue(const std::string& key, double value, BirotorParams* params) {
  if (key == "arm_stiffness_n_m_rad")
    params->arm_stiffness_n_m_rad = value;
  else if (key == "arm_damping_n_m_s_rad")
    params->arm_damping_n_m_s_rad = value;
  else if (key == "thrust_coeff_n_s2_rad2")
    params->thrust_coeff_n_s2_rad2 = value;
  else if (key == "tip_mass_kg")
    params->tip_mass_kg = value;
  else if (key == "motor_time_constant_s")
    params->motor_time_constant_s = value;
  else if (key == "gauge_scale[0]")
    params->gauge_scale[0] = value;
  else if (key == "gauge_scale[1]")
    params->gauge_scale[1] = value;
  else if (key == "gauge_offset_rad[0]")
    params->gauge_offset_rad[0] = value;
  else if (key == "gauge_offset_rad[1]")
    params->gauge_offset_rad[1] = value;
  else
    return false;
  return true;
}

void StoreEstimates(const std::vector<ParameterEstimate>& estimates, IdentificationResult* result) {
  for (const ParameterEstimate& e : estimates) {
    if (e.determined) SetVehicleValue(e.key, e.value, &result->params);
    result->estimates.push_back(e);
  }
}

}  // namespace birotor
