// Bench arm fit (body clamped, load cells present): the stages of bench_fit.h
// and IdentifyBenchArms, which runs them.
#include <ceres/ceres.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "identification/bench_fit.h"
#include "identification/deflection_force_map.h"
#include "identification/fit_stages.h"
#include "identification/identify.h"
#include "identification/prior_residual.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {

constexpr size_t kMaxPlotPoints = 2000;  // per plot panel

}  // namespace

StaticLine FitStaticLine(const std::vector<double>& force_n, const std::vector<double>& reading_rad) {
  StaticLine line;
  const double n = static_cast<double>(force_n.size());
  if (n < 2) return line;
  double sf = 0.0, sy = 0.0, sff = 0.0, sfy = 0.0;
  for (size_t i = 0; i < force_n.size(); ++i) {
    sf += force_n[i];
    sy += reading_rad[i];
    sff += force_n[i] * force_n[i];
    sfy += force_n[i] * reading_rad[i];
  }
  const double det = n * sff - sf * sf;
  if (det <= 0.0) return line;
  line.slope_rad_n = (n * sfy - sf * sy) / det;
  line.intercept_rad = (sy - line.slope_rad_n * sf) / n;
  return line;
}

double CostWithBestInitialStates(const std::vector<ClampedArmWindowResidual*>& windows, const double* theta) {
  double total = 0.0;
  const double probe[2] = {1e-4, 1e-2};  // [rad], [rad/s]
  for (const ClampedArmWindowResidual* w : windows) {
    const int arm = w->arm_;
    const size_t n = w->samples_.size();
    std::vector<double> r0(n), r1(n), r2(n);
    const double zero[2] = {0.0, 0.0}, e1[2] = {probe[0], 0.0}, e2[2] = {0.0, probe[1]};
    const double* scale = &theta[kBenchScale1 + arm];
    const double* offset = &theta[kBenchOffset1 + arm];
    (*w)(&theta[kBenchK], &theta[kBenchD], &theta[kBenchTipMass], scale, offset, zero, r0.data());
    (*w)(&theta[kBenchK], &theta[kBenchD], &theta[kBenchTipMass], scale, offset, e1, r1.data());
    (*w)(&theta[kBenchK], &theta[kBenchD], &theta[kBenchTipMass], scale, offset, e2, r2.data());
    double a11 = 0.0, a12 = 0.0, a22 = 0.0, g1 = 0.0, g2 = 0.0, c0 = 0.0;
    for (size_t j = 0; j < n; ++j) {
      const double j1 = r1[j] - r0[j], j2 = r2[j] - r0[j];
      a11 += j1 * j1;
      a12 += j1 * j2;
      a22 += j2 * j2;
      g1 += j1 * r0[j];
      g2 += j2 * r0[j];
      c0 += r0[j] * r0[j];
    }
    const double det = a11 * a22 - a12 * a12;
    if (det <= 0.0) {
      total += c0;
      continue;
    }
    // min |r0 + J x|^2 = c0 - g^T A^-1 g.
    total += c0 - (a22 * g1 * g1 - 2.0 * a12 * g1 * g2 + a11 * g2 * g2) / det;
  }
  return total;
}

void FitBenchMaps(const std::vector<double> map_b[kBirotorRotors], const std::vector<double> map_f[kBirotorRotors],
                  const IdentificationOptions& options, IdentificationResult* result) {
  for (int arm = 0; arm < kBirotorRotors; ++arm) {
    DeflectionForceMap map = FitDeflectionForceMap(arm, map_b[arm], map_f[arm], options.map_degree);
    if (map.samples == 0) continue;
    result->maps.push_back(map);
    // Map and its residuals against deflection.
    FitPlot fit, residual;
    fit.panel = FitPanel::kArmMap;
    fit.value = options.map_degree;
    residual.panel = FitPanel::kArmMapResidual;
    residual.value = map.residual_rms_n;
    fit.arm = residual.arm = arm;
    const size_t stride = map_b[arm].size() / kMaxPlotPoints + 1;
    for (size_t i = 0; i < map_b[arm].size(); i += stride) {
      const double model = EvaluateMap(map, map_b[arm][i]);
      fit.x.push_back(1e3 * map_b[arm][i]);
      fit.data.push_back(map_f[arm][i]);
      fit.model.push_back(model);
      residual.x.push_back(1e3 * map_b[arm][i]);
      residual.data.push_back(map_f[arm][i] - model);
      residual.model.push_back(0.0);
    }
    result->plots.push_back(std::move(fit));
    result->plots.push_back(std::move(residual));
  }
}

BenchStatics BenchArmStatics(const std::vector<double> map_b[kBirotorRotors],
                             const std::vector<double> map_f[kBirotorRotors], const BirotorParams& base,
                             const CalibrationFact& fact) {
  BenchStatics statics;
  for (int arm = 0; arm < kBirotorRotors; ++arm) statics.lines[arm] = FitStaticLine(map_f[arm], map_b[arm]);
  statics.scales.stiffness_n_m_rad = base.arm_stiffness_n_m_rad;
  statics.scales.damping_n_m_s_rad = base.arm_damping_n_m_s_rad > 0.0 ? base.arm_damping_n_m_s_rad : 0.1;
  statics.scales.tip_mass_kg = base.tip_mass_kg;
  statics.tip_mass_kg = fact.TipMassWeighed() ? fact.tip_mass_kg : base.tip_mass_kg;
  for (int arm = 0; arm < kBirotorRotors; ++arm) {
    const double c = statics.lines[arm].slope_rad_n * kArmSign[arm];
    statics.stiffness_n_m_rad +=
        0.5 * (c > 0.0 ? base.gauge_scale[arm] * base.arm_length_m / c : base.arm_stiffness_n_m_rad);
  }
  return statics;
}

BenchTheta BenchThetaAt(const BenchStatics& statics, const BirotorParams& base, double strain_noise_rad,
                        double stiffness_n_m_rad, double tip_mass_kg, const double gauge_scale[kBirotorRotors]) {
  BenchTheta theta;
  theta[kBenchK] = stiffness_n_m_rad / statics.scales.stiffness_n_m_rad;
  theta[kBenchD] = base.arm_damping_n_m_s_rad / statics.scales.damping_n_m_s_rad;
  theta[kBenchTipMass] = tip_mass_kg / statics.scales.tip_mass_kg;
  for (int arm = 0; arm < kBirotorRotors; ++arm) {
    theta[kBenchScale1 + arm] = gauge_scale[arm];
    // Slope implied by s_i, k; the offset from the intercept a = o - c m_p g.
    const double c = kArmSign[arm] * gauge_scale[arm] * base.arm_length_m / stiffness_n_m_rad;
    theta[kBenchOffset1 + arm] =
        (statics.lines[arm].intercept_rad + c * tip_mass_kg * base.gravity_m_s2) / strain_noise_rad;
  }
  return theta;
}

BenchTheta ScanArmFrequency(const std::vector<ArmData>& data, const std::vector<ArmWindow>& windows,
                            const BenchStatics& statics, const BirotorParams& base,
                            const IdentificationOptions& options) {
  const CalibrationFact& fact = options.calibration;
  const bool weighed = fact.TipMassWeighed();
  const bool scale_free = weighed || fact.gauge_scale_std > 0.0;
  const bool scales_move = scale_free && weighed;
  // theta at the frequency factor q (k / m_p times q).
  auto at = [&](double q) {
    if (scales_move) {
      const double gauge_scale[kBirotorRotors] = {base.gauge_scale[0] * q, base.gauge_scale[1] * q};
      return BenchThetaAt(statics, base, options.strain_noise_rad, statics.stiffness_n_m_rad * q, statics.tip_mass_kg,
                          gauge_scale);
    }
    return BenchThetaAt(statics, base, options.strain_noise_rad, statics.stiffness_n_m_rad, statics.tip_mass_kg / q,
                        base.gauge_scale);
  };
  constexpr size_t kScanWindows = 24;
  std::vector<std::unique_ptr<ClampedArmWindowResidual>> probes;
  std::vector<ClampedArmWindowResidual*> scan;
  const size_t count = std::min(kScanWindows, windows.size());
  for (size_t w = 0; w < count; ++w) {
    const ArmWindow& spec = windows[(2 * w + 1) * windows.size() / (2 * count)];
    probes.push_back(std::make_unique<ClampedArmWindowResidual>(
        base, data[spec.data_index].arm, ArmWindowSamples(data, spec), options.strain_noise_rad,
        options.integration_substeps, statics.scales, options.huber_threshold));
    scan.push_back(probes.back().get());
  }
  double best_cost = std::numeric_limits<double>::infinity(), best_q = 1.0;
  for (double q = 0.5; q <= 2.0; q *= 1.03) {
    const BenchTheta theta = at(q);
    const double cost = CostWithBestInitialStates(scan, theta.data());
    if (cost < best_cost) {
      best_cost = cost;
      best_q = q;
    }
  }
  return at(best_q);
}

void BuildBenchArmProblem(const std::vector<ArmData>& data, const std::vector<ArmWindow>& windows,
                          const BenchStatics& statics, const BirotorParams& base, const IdentificationOptions& options,
                          BenchArmProblem* fit) {
  const CalibrationFact& fact = options.calibration;
  const bool weighed = fact.TipMassWeighed();
  const bool mass_free = !weighed || fact.tip_mass_std_kg > 0.0;
  const bool scale_free = weighed || fact.gauge_scale_std > 0.0;
  const double sigma_b = options.strain_noise_rad;
  ceres::Problem& problem = fit->problem;
  double* p = fit->theta.data();
  for (const ArmWindow& w : windows) {
    const ArmData& d = data[w.data_index];
    const int arm = d.arm;
    // Initial state: static deflection under the first force, at rest.
    const double reading_rad = statics.lines[arm].intercept_rad + statics.lines[arm].slope_rad_n * d.force_n[w.begin];
    fit->states.push_back({(reading_rad - p[kBenchOffset1 + arm] * sigma_b) / p[kBenchScale1 + arm], 0.0});
    fit->blocks.push_back(problem.AddResidualBlock(
        ClampedArmWindowResidual::Create(base, arm, ArmWindowSamples(data, w), sigma_b, options.integration_substeps,
                                         statics.scales, options.huber_threshold),
        nullptr, &p[kBenchK], &p[kBenchD], &p[kBenchTipMass], &p[kBenchScale1 + arm], &p[kBenchOffset1 + arm],
        fit->states.back().data()));
  }
  problem.SetParameterLowerBound(&p[kBenchK], 0, 1e-3);
  problem.SetParameterLowerBound(&p[kBenchD], 0, 0.0);
  problem.SetParameterLowerBound(&p[kBenchTipMass], 0, 1e-3);
  if (!mass_free) problem.SetParameterBlockConstant(&p[kBenchTipMass]);
  if (weighed && fact.tip_mass_std_kg > 0.0) {
    problem.AddResidualBlock(PriorResidual::Create(fact.tip_mass_kg / statics.scales.tip_mass_kg,
                                                   fact.tip_mass_std_kg / statics.scales.tip_mass_kg),
                             nullptr, &p[kBenchTipMass]);
  }
  for (int arm = 0; arm < kBirotorRotors; ++arm) {
    double* s = &p[kBenchScale1 + arm];
    if (!problem.HasParameterBlock(s)) continue;
    problem.SetParameterLowerBound(s, 0, 0.1);
    if (!scale_free) {
      problem.SetParameterBlockConstant(s);
    } else if (fact.gauge_scale_std > 0.0) {
      problem.AddResidualBlock(PriorResidual::Create(base.gauge_scale[arm], fact.gauge_scale_std), nullptr, s);
    }
  }
}

namespace {

// Floor stage of the bench arm fit: what the sampled load-cell input cannot
// give better (options), on d and on k / m_p; the offsets follow m_p through
// the static intercept, the scales follow k when the tip mass is weighed.
void AddBenchArmFloors(const IdentificationOptions& options, const BenchTheta& theta, const BirotorParams& base,
                       ParameterEstimate* k, ParameterEstimate* damping, ParameterEstimate* tip_mass,
                       ParameterEstimate scale[kBirotorRotors], ParameterEstimate offset[kBirotorRotors]) {
  const CalibrationFact& fact = options.calibration;
  const bool weighed = fact.TipMassWeighed();
  const bool mass_free = !weighed || fact.tip_mass_std_kg > 0.0;
  const bool scale_free = weighed || fact.gauge_scale_std > 0.0;
  if (mass_free && !weighed) {
    AddBenchFloors(options, k, damping, tip_mass);
    // The offsets follow m_p through the static intercept, o_i = a_i + s_i sign_i L m_p g / k.
    for (int arm = 0; arm < kBirotorRotors; ++arm) {
      const double floor_rad = options.bench_frequency_floor * theta[kBenchScale1 + arm] * base.arm_length_m *
                               tip_mass->value * base.gravity_m_s2 / k->value;
      if (std::isfinite(offset[arm].value) && std::isfinite(floor_rad)) {
        offset[arm].sigma = std::hypot(offset[arm].sigma, floor_rad);
        offset[arm].note.remarks.push_back(EstimateRemark::kTipMassFloorThroughOffset);
      }
    }
  } else {
    AddRelativeFloor(damping, options.bench_damping_floor, EstimateRemark::kDampingFloor);
    AddRelativeFloor(k, options.bench_frequency_floor, EstimateRemark::kFrequencyFloor);
    for (int arm = 0; arm < kBirotorRotors; ++arm) {
      if (scale_free) {
        AddRelativeFloor(&scale[arm], options.bench_frequency_floor, EstimateRemark::kFrequencyFloor);
      }
    }
  }
}

}  // namespace

void IdentifyBenchArms(const std::vector<SensorLog>& logs, const BirotorParams& base,
                       const IdentificationOptions& options, IdentificationResult* result) {
  const CalibrationFact& fact = options.calibration;
  const double sigma_b = options.strain_noise_rad;
  std::vector<double> map_b[kBirotorRotors], map_f[kBirotorRotors];
  const std::vector<ArmData> data = CollectArmData(logs, map_b, map_f);
  FitBenchMaps(map_b, map_f, options, result);

  ParameterEstimate k = ParameterEstimate::Named("arm_stiffness_n_m_rad", "k");
  ParameterEstimate damping = ParameterEstimate::Named("arm_damping_n_m_s_rad", "d");
  ParameterEstimate tip_mass = ParameterEstimate::Named("tip_mass_kg", "m_p");
  ParameterEstimate scale[kBirotorRotors], offset[kBirotorRotors];
  for (int arm = 0; arm < kBirotorRotors; ++arm) {
    scale[arm] = ParameterEstimate::Named("gauge_scale[" + std::to_string(arm) + "]", "s_" + std::to_string(arm + 1));
    offset[arm] =
        ParameterEstimate::Named("gauge_offset_rad[" + std::to_string(arm) + "]", "o_" + std::to_string(arm + 1));
  }
  if (map_f[0].size() < 20 || map_f[1].size() < 20) {
    result->errors.push_back("k, d, m_p: no STRAIN samples paired with LOADCELL samples");
    result->estimates.insert(result->estimates.end(), {k, damping, tip_mass});
    return;
  }
  // Which of s_i, m_p carries the outside fact (gauges.md).
  const bool weighed = fact.TipMassWeighed();
  const bool mass_free = !weighed || fact.tip_mass_std_kg > 0.0;
  const bool scale_free = weighed || fact.gauge_scale_std > 0.0;
  result->has_calibration_fact = true;
  result->calibration_fact = fact;
  for (int arm = 0; arm < kBirotorRotors; ++arm) result->factory_gauge_scale[arm] = base.gauge_scale[arm];

  const BenchStatics statics = BenchArmStatics(map_b, map_f, base, fact);
  const std::vector<ArmWindow> windows = ArmWindows(data, options);
  BenchArmProblem fit;
  ReportProgress(options, {"bench: arm frequency scan", static_cast<int>(windows.size()), 0, 0.2});
  fit.theta = ScanArmFrequency(data, windows, statics, base, options);
  BuildBenchArmProblem(data, windows, statics, base, options, &fit);
  const FitProgress solving{"bench: arm solve", static_cast<int>(windows.size()), 0, 0.3};
  SolveProblem(options, &fit.problem, 1e-10, &solving);
  ReportProgress(options, {"bench: arm sigmas", static_cast<int>(windows.size()), 0, 0.8});
  const ResidualStatistics stats = ComputeResidualStatistics(&fit.problem, fit.blocks, 1, 0);
  const double inflation = VarianceInflation(stats);

  const double units[kBenchArmParameters] = {statics.scales.stiffness_n_m_rad,
                                             statics.scales.damping_n_m_s_rad,
                                             statics.scales.tip_mass_kg,
                                             1.0,
                                             1.0,
                                             sigma_b,
                                             sigma_b};
  ParameterEstimate* estimates[kBenchArmParameters] = {&k,        &damping,   &tip_mass, &scale[0],
                                                       &scale[1], &offset[0], &offset[1]};
  std::vector<RatioParameter> free;
  for (int i = 0; i < kBenchArmParameters; ++i) {
    double* block = &fit.theta[i];
    if (!fit.problem.HasParameterBlock(block) || fit.problem.IsParameterBlockConstant(block)) continue;
    // An offset may be zero: judged against the strain noise instead.
    const bool is_offset = i == kBenchOffset1 || i == kBenchOffset2;
    free.push_back({estimates[i], block, units[i], is_offset ? sigma_b : 0.0});
  }
  std::vector<double*> free_blocks;
  for (const RatioParameter& p : free) free_blocks.push_back(p.ratio);
  const std::vector<BlockSigma> sigma = SharedSigmas(&fit.problem, free_blocks, inflation, {}, options.num_threads);
  EstimateNote note;
  note.basis = EstimateBasis::kClampedArmFit;
  note.windows = static_cast<int>(fit.blocks.size());
  for (size_t n = 0; n < free.size(); ++n) FillEstimate(free[n], sigma[n], options.max_relative_sigma, note);
  AddBenchArmFloors(options, fit.theta, base, &k, &damping, &tip_mass, scale, offset);
  if (stats.rms_whitened > options.misfit_rms_warn) {
    IdentificationWarning misfit;
    misfit.kind = WarningKind::kArmModelMisfit;
    misfit.value = stats.rms_whitened;
    result->warnings.push_back(misfit);
    for (ParameterEstimate* e : estimates) e->note.remarks.push_back(EstimateRemark::kWidenedForMisfit);
  }
  const std::vector<DeterminedCombination> correlations = CorrelationLines(&fit.problem, free, options.num_threads);
  result->correlations.insert(result->correlations.end(), correlations.begin(), correlations.end());
  if (!k.determined) result->errors.push_back("k: not determined by the bench strain data (no force variation)");
  if (!damping.determined) result->warnings.push_back({WarningKind::kNotExcitedOnBench, "d"});
  std::vector<ParameterEstimate> stored = {k, damping};
  if (mass_free) {
    if (!tip_mass.determined) result->warnings.push_back({WarningKind::kNotExcitedOnBench, "m_p"});
    stored.push_back(tip_mass);
  }
  for (int arm = 0; arm < kBirotorRotors; ++arm) {
    if (scale_free) {
      if (!scale[arm].determined) result->errors.push_back(scale[arm].symbol + ": gauge scale not determined");
      stored.push_back(scale[arm]);
    }
    if (!offset[arm].determined) result->errors.push_back(offset[arm].symbol + ": gauge offset not determined");
    stored.push_back(offset[arm]);
  }
  result->residuals.push_back(
      {ResidualBlock::kClampedArm, stats.count, stats.rms_whitened, stats.rms_whitened * sigma_b, inflation});
  StoreEstimates(stored, result);
  if (!mass_free) result->params.tip_mass_kg = fact.tip_mass_kg;
}

}  // namespace birotor
