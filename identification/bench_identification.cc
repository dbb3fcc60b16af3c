// Bench identification (body clamped, load cells present): c_T from load-cell
// force against telemetry, the paired strain/load-cell data of the arm fit
// (bench_arm_fit.cc) and the bench residuals of a joint bench + flight fit.
#include <ceres/ceres.h>

#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <string>

#include "identification/bench_fit.h"
#include "identification/bench_residuals.h"
#include "identification/fit_support.h"
#include "identification/identify.h"
#include "identification/prior_residual.h"
#include "identification/thrust_residual.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {

constexpr int64_t kMaxLoadCellGapUs = 5000;  // interpolate load cells over at most 5 ms
constexpr size_t kMaxPlotPoints = 2000;      // per plot panel

double LoadCellForce(const LoadCellSample& s, int rotor) { return s.force_n[rotor]; }

// Load-cell/telemetry pairs thrust_sample_spacing_s apart on the c_T ratio
// block (ThrustResidual, Huber loss), with their data for the plot (may be null).
std::vector<ceres::ResidualBlockId> AddThrustResiduals(const std::vector<SensorLog>& logs, const BirotorParams& base,
                                                       const IdentificationOptions& options, ceres::Problem* problem,
                                                       double* c_ratio, std::vector<double>* plot_omega,
                                                       std::vector<double>* plot_force) {
  std::vector<ceres::ResidualBlockId> blocks;
  const int64_t spacing_us = static_cast<int64_t>(options.thrust_sample_spacing_s * 1e6);
  for (const SensorLog& log : logs) {
    for (int rotor = 0; rotor < kBirotorRotors; ++rotor) {
      size_t hint = 0;
      int64_t next_us = std::numeric_limits<int64_t>::min();
      for (const MotorSample& m : log.motor) {
        const double omega = m.omega_meas_rad_s[rotor];
        if (m.utime < next_us || !std::isfinite(omega)) continue;
        double force = 0.0;
        if (!InterpolateAt(
                log.loadcell, m.utime, kMaxLoadCellGapUs, &hint,
                [rotor](const LoadCellSample& s) { return LoadCellForce(s, rotor); }, &force) ||
            !std::isfinite(force)) {
          continue;
        }
        next_us = m.utime + spacing_us;
        if (plot_omega != nullptr) plot_omega->push_back(omega);
        if (plot_force != nullptr) plot_force->push_back(force);
        const double f_model = base.thrust_coeff_n_s2_rad2 * omega * omega;
        const double dfdw = 2.0 * base.thrust_coeff_n_s2_rad2 * std::abs(omega) * options.telemetry_noise_rad_s;
        const double sigma = std::sqrt(options.loadcell_noise_n * options.loadcell_noise_n +
                                       std::pow(base.turbulence_std * f_model, 2) + dfdw * dfdw);
        blocks.push_back(
            problem->AddResidualBlock(ThrustResidual::Create(force, omega, sigma, base.thrust_coeff_n_s2_rad2),
                                      new ceres::HuberLoss(options.huber_threshold), c_ratio));
      }
    }
  }
  return blocks;
}

}  // namespace

double ThrustResidualRmsN(const std::vector<SensorLog>& logs, double thrust_coeff_n_s2_rad2) {
  double sum_sq = 0.0;
  int count = 0;
  for (const SensorLog& log : logs) {
    for (int rotor = 0; rotor < kBirotorRotors; ++rotor) {
      size_t hint = 0;
      for (const MotorSample& m : log.motor) {
        double force = 0.0;
        const double omega = m.omega_meas_rad_s[rotor];
        if (!std::isfinite(omega) ||
            !InterpolateAt(
                log.loadcell, m.utime, kMaxLoadCellGapUs, &hint,
                [rotor](const LoadCellSample& s) { return LoadCellForce(s, rotor); }, &force)) {
          continue;
        }
        sum_sq += std::pow(force - thrust_coeff_n_s2_rad2 * omega * omega, 2);
        ++count;
      }
    }
  }
  return count > 0 ? std::sqrt(sum_sq / count) : 0.0;
}

void IdentifyBenchThrust(const std::vector<SensorLog>& logs, const BirotorParams& base,
                         const IdentificationOptions& options, IdentificationResult* result) {
  ceres::Problem problem;
  double ratio = 1.0;
  std::vector<double> plot_omega, plot_force;
  const std::vector<ceres::ResidualBlockId> blocks =
      AddThrustResiduals(logs, base, options, &problem, &ratio, &plot_omega, &plot_force);
  ParameterEstimate c_t;
  c_t.key = "thrust_coeff_n_s2_rad2";
  c_t.symbol = "c_T";
  if (blocks.size() < 10) {
    result->errors.push_back("c_T: fewer than 10 LOADCELL samples paired with MOTOR telemetry");
    result->estimates.push_back(c_t);
    return;
  }
  SolveProblem(options, &problem);
  const ResidualStatistics stats = ComputeResidualStatistics(&problem, blocks, 1, 0);
  const double inflation = std::max(1.0, stats.robust_scale * stats.robust_scale);
  const std::vector<BlockSigma> sigma = ComputeBlockSigmas(&problem, {&ratio}, inflation, options.num_threads);
  c_t.value = ratio * base.thrust_coeff_n_s2_rad2;
  c_t.sigma = sigma[0].sigma * base.thrust_coeff_n_s2_rad2;
  c_t.determined = SigmaDetermines(sigma[0].determined, c_t.value, c_t.sigma, options.max_relative_sigma);
  c_t.note.basis = EstimateBasis::kThrustPairs;
  c_t.note.windows = static_cast<int>(blocks.size());
  c_t.note.spacing_s = options.thrust_sample_spacing_s;
  if (!c_t.determined) result->errors.push_back("c_T: not determined by the load-cell data (no thrust variation)");
  result->estimates.push_back(c_t);
  result->residuals.push_back({ResidualBlock::kLoadCell, stats.count, stats.rms_whitened, 0.0, inflation});
  result->residuals.back().rms_si = ThrustResidualRmsN(logs, c_t.value);
  if (c_t.determined) result->params.thrust_coeff_n_s2_rad2 = c_t.value;
  FitPlot plot;
  plot.panel = FitPanel::kThrustMap;
  const size_t stride = plot_omega.size() / kMaxPlotPoints + 1;
  for (size_t i = 0; i < plot_omega.size(); i += stride) {
    plot.x.push_back(plot_omega[i]);
    plot.data.push_back(plot_force[i]);
    plot.model.push_back(c_t.value * plot_omega[i] * plot_omega[i]);
  }
  result->plots.push_back(std::move(plot));
}

// Strain samples of every (log, arm) with the load-cell force at the same
// time; the valid pairs also go to map_b, map_f (the static map's data).
std::vector<ArmData> CollectArmData(const std::vector<SensorLog>& logs, std::vector<double> map_b[kBirotorRotors],
                                    std::vector<double> map_f[kBirotorRotors]) {
  std::vector<ArmData> data;  // per (log, arm)
  for (const SensorLog& log : logs) {
    for (int arm = 0; arm < kBirotorRotors; ++arm) {
      ArmData d;
      d.arm = arm;
      size_t hint = 0;
      for (const StrainSample& s : log.strain) {
        double force = 0.0;
        const bool ok = InterpolateAt(
                            log.loadcell, s.utime, kMaxLoadCellGapUs, &hint,
                            [arm](const LoadCellSample& c) { return LoadCellForce(c, arm); }, &force) &&
                        std::isfinite(force) && std::isfinite(s.deflection_rad[arm]);
        d.utime.push_back(s.utime);
        d.deflection_rad.push_back(s.deflection_rad[arm]);
        d.force_n.push_back(ok ? force : 0.0);
        d.valid.push_back(ok);
        if (ok) {
          map_b[arm].push_back(s.deflection_rad[arm]);
          map_f[arm].push_back(force);
        }
      }
      data.push_back(std::move(d));
    }
  }
  return data;
}

// Windows of bench_arm_window_s over every (log, arm) run of valid pairs.
std::vector<ArmWindow> ArmWindows(const std::vector<ArmData>& data, const IdentificationOptions& options) {
  std::vector<ArmWindow> windows;
  for (size_t n = 0; n < data.size(); ++n) {
    const ArmData& d = data[n];
    const int64_t max_gap_us = 3 * std::max<int64_t>(MedianIntervalUs(d.utime), 1);
    for (const auto& [begin, end] : ContiguousWindows(d.utime, d.valid, options.bench_arm_window_s, max_gap_us, 20)) {
      windows.push_back({n, begin, end});
    }
  }
  return windows;
}

std::vector<ClampedArmWindowResidual::Sample> ArmWindowSamples(const std::vector<ArmData>& data, const ArmWindow& w) {
  const ArmData& d = data[w.data_index];
  std::vector<ClampedArmWindowResidual::Sample> samples;
  samples.reserve(w.end - w.begin);
  for (size_t i = w.begin; i < w.end; ++i) {
    const double dt_s = (i + 1 < w.end) ? 1e-6 * static_cast<double>(d.utime[i + 1] - d.utime[i]) : 0.0;
    samples.push_back({dt_s, d.force_n[i], d.deflection_rad[i]});
  }
  return samples;
}

void AddBenchResiduals(const std::vector<SensorLog>& logs, const BirotorParams& bench,
                       const IdentificationOptions& options, ceres::Problem* problem, const SharedRatioBlocks& shared,
                       BenchResiduals* out) {
  out->thrust = AddThrustResiduals(logs, bench, options, problem, shared.thrust_coeff, nullptr, nullptr);
  std::vector<double> map_b[kBirotorRotors], map_f[kBirotorRotors];
  const std::vector<ArmData> data = CollectArmData(logs, map_b, map_f);
  const double sigma_b = options.strain_noise_rad;
  ClampedArmWindowResidual::Scales scales;
  scales.stiffness_n_m_rad = bench.arm_stiffness_n_m_rad;
  scales.damping_n_m_s_rad = bench.arm_damping_n_m_s_rad > 0.0 ? bench.arm_damping_n_m_s_rad : 0.1;
  scales.tip_mass_kg = bench.tip_mass_kg;
  for (int arm = 0; arm < kBirotorRotors; ++arm) {
    out->gauge_scale[arm] = bench.gauge_scale[arm];
    out->offset_ratio[arm] = bench.gauge_offset_rad[arm] / sigma_b;
  }
  for (const ArmWindow& w : ArmWindows(data, options)) {
    const ArmData& d = data[w.data_index];
    const int arm = d.arm;
    // Initial state: the first reading through the gauge, at rest.
    out->states.push_back({(d.deflection_rad[w.begin] - bench.gauge_offset_rad[arm]) / bench.gauge_scale[arm], 0.0});
    out->arms.push_back(problem->AddResidualBlock(
        ClampedArmWindowResidual::Create(bench, arm, ArmWindowSamples(data, w), sigma_b, options.integration_substeps,
                                         scales, options.huber_threshold),
        nullptr, shared.stiffness, shared.damping, shared.tip_mass, &out->gauge_scale[arm], &out->offset_ratio[arm],
        out->states.back().data()));
  }
  for (int arm = 0; arm < kBirotorRotors; ++arm) {
    if (!problem->HasParameterBlock(&out->gauge_scale[arm])) continue;
    problem->SetParameterBlockConstant(&out->gauge_scale[arm]);
    problem->SetParameterBlockConstant(&out->offset_ratio[arm]);
  }
  const CalibrationFact& fact = options.calibration;
  if (fact.TipMassWeighed() && problem->HasParameterBlock(shared.tip_mass)) {
    if (fact.tip_mass_std_kg > 0.0) {
      problem->AddResidualBlock(
          PriorResidual::Create(fact.tip_mass_kg / scales.tip_mass_kg, fact.tip_mass_std_kg / scales.tip_mass_kg),
          nullptr, shared.tip_mass);
    } else {
      problem->SetParameterBlockConstant(shared.tip_mass);
    }
  }
}

}  // namespace birotor
