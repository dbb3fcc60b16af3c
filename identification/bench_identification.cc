// Bench identification (body clamped, load cells present): c_T from load-cell
// force against telemetry, k and d from the clamped arm response to the
// measured force, and the static deflection-force map of each arm.
#include <ceres/ceres.h>

#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <sstream>
#include <string>

#include "identification/clamped_arm_residual.h"
#include "identification/deflection_force_map.h"
#include "identification/fit_support.h"
#include "identification/identify.h"
#include "identification/thrust_residual.h"

namespace birotor {
namespace {

constexpr int64_t kMaxLoadCellGapUs = 5000;  // interpolate load cells over at most 5 ms
constexpr size_t kMaxPlotPoints = 2000;      // per plot panel

double LoadCellForce(const LoadCellSample& s, int rotor) { return s.force_n[rotor]; }

}  // namespace

void IdentifyBenchThrust(const std::vector<SensorLog>& logs, const VehicleParams& base,
                         const IdentificationOptions& options, IdentificationResult* result) {
  ceres::Problem problem;
  double ratio = 1.0;
  std::vector<ceres::ResidualBlockId> blocks;
  std::vector<double> plot_omega, plot_force;
  const int64_t spacing_us = static_cast<int64_t>(options.thrust_sample_spacing_s * 1e6);
  for (const SensorLog& log : logs) {
    for (int rotor = 0; rotor < 2; ++rotor) {
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
        plot_omega.push_back(omega);
        plot_force.push_back(force);
        const double f_model = base.thrust_coeff_n_s2_rad2 * omega * omega;
        const double dfdw = 2.0 * base.thrust_coeff_n_s2_rad2 * std::abs(omega) * options.telemetry_noise_rad_s;
        const double sigma = std::sqrt(options.loadcell_noise_n * options.loadcell_noise_n +
                                       std::pow(base.turbulence_std * f_model, 2) + dfdw * dfdw);
        blocks.push_back(
            problem.AddResidualBlock(ThrustResidual::Create(force, omega, sigma, base.thrust_coeff_n_s2_rad2),
                                     new ceres::HuberLoss(options.huber_threshold), &ratio));
      }
    }
  }
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
  c_t.determined = sigma[0].determined && c_t.sigma <= options.max_relative_sigma * std::abs(c_t.value);
  std::ostringstream note;
  note << blocks.size() << " load-cell/telemetry pairs " << options.thrust_sample_spacing_s
       << " s apart (turbulence averaged)";
  c_t.note = note.str();
  if (!c_t.determined) result->errors.push_back("c_T: not determined by the load-cell data (no thrust variation)");
  result->estimates.push_back(c_t);
  result->residuals.push_back(
      {"load cell (force - c_T omega^2)", "N", stats.count, stats.rms_whitened, 0.0, inflation});
  // RMS in newtons, without whitening (sigma differs per sample).
  double sum_sq = 0.0;
  int count = 0;
  for (const SensorLog& log : logs) {
    for (int rotor = 0; rotor < 2; ++rotor) {
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
        sum_sq += std::pow(force - c_t.value * omega * omega, 2);
        ++count;
      }
    }
  }
  result->residuals.back().rms_si = count > 0 ? std::sqrt(sum_sq / count) : 0.0;
  if (c_t.determined) result->params.thrust_coeff_n_s2_rad2 = c_t.value;
  FitPlot plot;
  plot.title = "thrust: load cell vs c_T omega^2 (both rotors)";
  plot.x_label = "omega (telemetry) [rad/s]";
  plot.y_label = "force [N]";
  const size_t stride = plot_omega.size() / kMaxPlotPoints + 1;
  for (size_t i = 0; i < plot_omega.size(); i += stride) {
    plot.x.push_back(plot_omega[i]);
    plot.data.push_back(plot_force[i]);
    plot.model.push_back(c_t.value * plot_omega[i] * plot_omega[i]);
  }
  result->plots.push_back(std::move(plot));
}

void IdentifyBenchArms(const std::vector<SensorLog>& logs, const VehicleParams& base,
                       const IdentificationOptions& options, IdentificationResult* result) {
  const double k_scale = base.arm_stiffness_n_m_rad;
  const double d_scale = base.arm_damping_n_m_s_rad > 0.0 ? base.arm_damping_n_m_s_rad : 0.1;
  const double mp_g = base.tip_mass_kg * base.gravity_m_s2;
  const double L = base.arm_length_m;

  // Paired strain/load-cell samples of each arm, and the static guess of k
  // from k b = s_i L (f - m_p g) (least squares through the origin).
  struct ArmData {
    std::vector<int64_t> utime;
    std::vector<double> deflection_rad, force_n;
    std::vector<bool> valid;
  };
  std::vector<ArmData> data;  // per (log, arm)
  double sxy = 0.0, sxx = 0.0;
  std::vector<double> map_b[2], map_f[2];
  for (const SensorLog& log : logs) {
    for (int arm = 0; arm < 2; ++arm) {
      ArmData d;
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
          const double y = kArmSign[arm] * L * (force - mp_g);
          sxy += y * s.deflection_rad[arm];
          sxx += s.deflection_rad[arm] * s.deflection_rad[arm];
          map_b[arm].push_back(s.deflection_rad[arm]);
          map_f[arm].push_back(force);
        }
      }
      data.push_back(std::move(d));
    }
  }
  for (int arm = 0; arm < 2; ++arm) {
    DeflectionForceMap map = FitDeflectionForceMap(arm, map_b[arm], map_f[arm], options.map_degree);
    if (map.samples == 0) continue;
    result->maps.push_back(map);
    // Map and its residuals against deflection.
    FitPlot fit, residual;
    fit.title = "arm " + std::to_string(arm + 1) + ": load cell force vs deflection map (degree " +
                std::to_string(options.map_degree) + ")";
    residual.title =
        "arm " + std::to_string(arm + 1) + ": map residual (RMS " + std::to_string(map.residual_rms_n) + " N)";
    fit.x_label = residual.x_label = "deflection b" + std::to_string(arm + 1) + " [mrad]";
    fit.y_label = "force [N]";
    residual.y_label = "force - map [N]";
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

  ceres::Problem problem;
  double k_ratio = (sxx > 0.0 && sxy > 0.0) ? (sxy / sxx) / k_scale : 1.0;
  double d_ratio = base.arm_damping_n_m_s_rad / d_scale;
  std::deque<std::array<double, 2>> states;
  std::vector<ceres::ResidualBlockId> blocks;
  for (size_t n = 0; n < data.size(); ++n) {
    const int arm = static_cast<int>(n % 2);
    const ArmData& d = data[n];
    const int64_t max_gap_us = 3 * std::max<int64_t>(MedianIntervalUs(d.utime), 1);
    for (const auto& [begin, end] : ContiguousWindows(d.utime, d.valid, options.bench_arm_window_s, max_gap_us, 20)) {
      std::vector<ClampedArmWindowResidual::Sample> samples;
      samples.reserve(end - begin);
      for (size_t i = begin; i < end; ++i) {
        const double dt_s = (i + 1 < end) ? 1e-6 * static_cast<double>(d.utime[i + 1] - d.utime[i]) : 0.0;
        samples.push_back({dt_s, d.force_n[i], d.deflection_rad[i]});
      }
      // Initial state: static deflection under the first force, at rest.
      states.push_back({kArmSign[arm] * L * (d.force_n[begin] - mp_g) / (k_ratio * k_scale), 0.0});
      blocks.push_back(problem.AddResidualBlock(
          ClampedArmWindowResidual::Create(base, arm, std::move(samples), options.strain_noise_rad,
                                           options.integration_substeps, k_scale, d_scale, options.huber_threshold),
          nullptr, &k_ratio, &d_ratio, states.back().data()));
    }
  }
  ParameterEstimate k, damping;
  k.key = "arm_stiffness_n_m_rad";
  k.symbol = "k";
  damping.key = "arm_damping_n_m_s_rad";
  damping.symbol = "d";
  if (blocks.empty()) {
    result->errors.push_back("k, d: no STRAIN samples paired with LOADCELL samples");
    result->estimates.push_back(k);
    result->estimates.push_back(damping);
    return;
  }
  problem.SetParameterLowerBound(&k_ratio, 0, 1e-3);
  problem.SetParameterLowerBound(&d_ratio, 0, 0.0);
  SolveProblem(options, &problem);
  const ResidualStatistics stats = ComputeResidualStatistics(&problem, blocks, 1, 0);
  const double inflation = VarianceInflation(stats);
  const std::vector<BlockSigma> sigma =
      ComputeBlockSigmas(&problem, {&k_ratio, &d_ratio}, inflation, options.num_threads);
  k.value = k_ratio * k_scale;
  k.sigma = sigma[0].sigma * k_scale;
  k.determined = sigma[0].determined && k.sigma <= options.max_relative_sigma * k.value;
  k.note = "output error of the clamped arm over " + std::to_string(blocks.size()) + " windows";
  damping.value = d_ratio * d_scale;
  damping.sigma = sigma[1].sigma * d_scale;
  damping.determined = sigma[1].determined && damping.sigma <= options.max_relative_sigma * damping.value;
  damping.note = k.note;
  if (!k.determined) result->errors.push_back("k: not determined by the bench strain data (no force variation)");
  if (!damping.determined) {
    result->warnings.push_back("d: not determined (the arm modes are barely excited); base value kept");
  }
  result->estimates.push_back(k);
  result->estimates.push_back(damping);
  result->residuals.push_back({"strain (clamped arm model)", "rad", stats.count, stats.rms_whitened,
                               stats.rms_whitened * options.strain_noise_rad, inflation});
  if (k.determined) result->params.arm_stiffness_n_m_rad = k.value;
  if (damping.determined) result->params.arm_damping_n_m_s_rad = damping.value;
}

}  // namespace birotor
