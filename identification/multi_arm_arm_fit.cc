// The clamped-arm fit of one arm of an N-arm vehicle on the bench
// (multi_arm_bench_fit.h): the stages of the birotor's bench arm fit
// (bench_fit.h: data, statics, frequency scan, build, solve, sigmas, floors)
// on that arm's own hinge (ClampedArmGeometry), its gauge in slot 0.
#include <ceres/ceres.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "identification/bench_fit.h"
#include "identification/fit_stages.h"
#include "identification/fit_support.h"
#include "identification/multi_arm_fit_parts.h"

namespace birotor {
namespace {

constexpr int64_t kMaxLoadCellGapUs = 5000;  // interpolate load cells over at most 5 ms
constexpr size_t kScanWindows = 24;          // windows of the frequency scan

// theta (bench_fit.h layout, slot 0) at (k, m_p) holding the static line:
// reading = s b + o with b = (l f - m_p g L cos alpha) / k at rest, so the
// intercept a = o - s m_p g L cos alpha / k gives o.
BenchTheta ArmThetaAt(const StaticLine& line, const ClampedArmWindowResidual::Scales& scales,
                      const ClampedArmGeometry& geometry, double gauge_scale, double damping, double stiffness,
                      double tip_mass, double strain_noise_rad) {
  BenchTheta theta{};
  theta[kBenchK] = stiffness / scales.stiffness_n_m_rad;
  theta[kBenchD] = damping / scales.damping_n_m_s_rad;
  theta[kBenchTipMass] = tip_mass / scales.tip_mass_kg;
  theta[kBenchScale1] = gauge_scale;
  theta[kBenchScale2] = 1.0;
  const double weight_reading =
      gauge_scale * tip_mass * geometry.gravity_m_s2 * geometry.length_m * geometry.cos_angle / stiffness;
  theta[kBenchOffset1] = (line.intercept_rad + weight_reading) / strain_noise_rad;
  return theta;
}

}  // namespace

std::vector<ArmData> CollectMultiArmData(const std::vector<MultiArmBenchLog>& logs, int arm, std::vector<double>* map_b,
                                         std::vector<double>* map_f) {
  std::vector<ArmData> data;
  const size_t i = static_cast<size_t>(arm);
  for (const MultiArmBenchLog& log : logs) {
    ArmData d;
    d.arm = 0;  // the gauge slot of the single-arm fit
    size_t hint = 0;
    for (const MultiArmStrainSample& s : log.strain) {
      double force = 0.0;
      const bool ok = InterpolateAt(
                          log.loadcell, s.utime, kMaxLoadCellGapUs, &hint,
                          [i](const MultiArmLoadCellSample& c) { return c.force_n[i]; }, &force) &&
                      std::isfinite(force) && std::isfinite(s.deflection_rad[i]);
      d.utime.push_back(s.utime);
      d.deflection_rad.push_back(s.deflection_rad[i]);
      d.force_n.push_back(ok ? force : 0.0);
      d.valid.push_back(ok);
      if (ok) {
        map_b->push_back(s.deflection_rad[i]);
        map_f->push_back(force);
      }
    }
    data.push_back(std::move(d));
  }
  return data;
}

// Start and scan: k from the static slope c = s l / k, m_p the description's,
// then the arm frequency k / m_p over a factor 4 in 3 % steps with m_p moving
// (the output-error cost has local minima a few percent apart in frequency).
ArmFitStart StartArmFit(const std::vector<ArmData>& data, const std::vector<ArmWindow>& windows,
                        const std::vector<double>& map_b, const std::vector<double>& map_f,
                        const VehicleDescription& base, int arm, const IdentificationOptions& options) {
  const ArmDescription& a = base.arms[static_cast<size_t>(arm)];
  ArmFitStart start;
  start.geometry = ClampedArmOf(base, arm);
  start.line = FitStaticLine(map_f, map_b);
  start.scales = {a.stiffness_n_m_rad, a.damping_n_m_s_rad > 0.0 ? a.damping_n_m_s_rad : 0.1, a.tip_mass_kg};
  const double slope = start.line.slope_rad_n;
  const double k0 = slope * a.gauge_scale * start.geometry.lever_m > 0.0
                        ? a.gauge_scale * start.geometry.lever_m / slope
                        : a.stiffness_n_m_rad;
  std::vector<std::unique_ptr<ClampedArmWindowResidual>> probes;
  std::vector<ClampedArmWindowResidual*> scan;
  const size_t count = std::min(kScanWindows, windows.size());
  for (size_t w = 0; w < count; ++w) {
    const ArmWindow& spec = windows[(2 * w + 1) * windows.size() / (2 * count)];
    probes.push_back(std::make_unique<ClampedArmWindowResidual>(start.geometry, 0, ArmWindowSamples(data, spec),
                                                                options.strain_noise_rad, options.integration_substeps,
                                                                start.scales, options.huber_threshold));
    scan.push_back(probes.back().get());
  }
  auto at = [&](double q) {
    return ArmThetaAt(start.line, start.scales, start.geometry, a.gauge_scale, a.damping_n_m_s_rad, k0,
                      a.tip_mass_kg / q, options.strain_noise_rad);
  };
  double best_cost = std::numeric_limits<double>::infinity(), best_q = 1.0;
  for (double q = 0.5; q <= 2.0; q *= 1.03) {
    const double cost = CostWithBestInitialStates(scan, at(q).data());
    if (cost < best_cost) {
      best_cost = cost;
      best_q = q;
    }
  }
  start.theta = at(best_q);
  return start;
}

// Build: one window residual per window over (k, d, m_p, s, o) of slot 0,
// each window starting at rest on the static line; s held (the factory fact).
void BuildArmProblem(const std::vector<ArmData>& data, const std::vector<ArmWindow>& windows, const ArmFitStart& start,
                     const IdentificationOptions& options, BenchArmProblem* fit) {
  const double sigma_b = options.strain_noise_rad;
  double* p = fit->theta.data();
  for (const ArmWindow& w : windows) {
    const ArmData& d = data[w.data_index];
    const double reading_rad = start.line.intercept_rad + start.line.slope_rad_n * d.force_n[w.begin];
    fit->states.push_back({(reading_rad - p[kBenchOffset1] * sigma_b) / p[kBenchScale1], 0.0});
    fit->blocks.push_back(fit->problem.AddResidualBlock(
        ClampedArmWindowResidual::Create(start.geometry, 0, ArmWindowSamples(data, w), sigma_b,
                                         options.integration_substeps, start.scales, options.huber_threshold),
        nullptr, &p[kBenchK], &p[kBenchD], &p[kBenchTipMass], &p[kBenchScale1], &p[kBenchOffset1],
        fit->states.back().data()));
  }
  fit->problem.SetParameterLowerBound(&p[kBenchK], 0, 1e-3);
  fit->problem.SetParameterLowerBound(&p[kBenchD], 0, 0.0);
  fit->problem.SetParameterLowerBound(&p[kBenchTipMass], 0, 1e-3);
  fit->problem.SetParameterBlockConstant(&p[kBenchScale1]);
}

// Solve, sigmas (information matrix, inflated), floors (AddBenchFloors and
// the tip-mass floor through the offset, as the birotor's bench fit) and the
// estimates of one arm.
void SolveArmFit(const ArmFitStart& start, const IdentificationOptions& options, BenchArmProblem* fit,
                 ArmEstimates* out) {
  const double sigma_b = options.strain_noise_rad;
  SolveProblem(options, &fit->problem, 1e-10);
  const ResidualStatistics stats = ComputeResidualStatistics(&fit->problem, fit->blocks, 1, 0);
  const double inflation = VarianceInflation(stats);
  out->strain_rms_whitened = stats.rms_whitened;
  double* p = fit->theta.data();
  const std::vector<RatioParameter> free = {{&out->stiffness, &p[kBenchK], start.scales.stiffness_n_m_rad, 0.0},
                                            {&out->damping, &p[kBenchD], start.scales.damping_n_m_s_rad, 0.0},
                                            {&out->tip_mass, &p[kBenchTipMass], start.scales.tip_mass_kg, 0.0},
                                            {&out->gauge_offset, &p[kBenchOffset1], sigma_b, sigma_b}};
  std::vector<double*> blocks;
  for (const RatioParameter& r : free) blocks.push_back(r.ratio);
  const std::vector<BlockSigma> sigma = SharedSigmas(&fit->problem, blocks, inflation, {}, options.num_threads);
  EstimateNote note;
  note.basis = EstimateBasis::kClampedArmFit;
  note.windows = static_cast<int>(fit->blocks.size());
  for (size_t n = 0; n < free.size(); ++n) FillEstimate(free[n], sigma[n], options.max_relative_sigma, note);
  AddBenchFloors(options, &out->stiffness, &out->damping, &out->tip_mass);
  // o = a + s m_p g L cos alpha / k: the frequency floor on m_p reaches o.
  const ClampedArmGeometry& g = start.geometry;
  const double floor_rad = options.bench_frequency_floor * p[kBenchScale1] * g.length_m * std::abs(g.cos_angle) *
                           out->tip_mass.value * g.gravity_m_s2 / out->stiffness.value;
  if (std::isfinite(out->gauge_offset.value) && std::isfinite(floor_rad)) {
    out->gauge_offset.sigma = std::hypot(out->gauge_offset.sigma, floor_rad);
    out->gauge_offset.note.remarks.push_back(EstimateRemark::kTipMassFloorThroughOffset);
  }
}

}  // namespace birotor
