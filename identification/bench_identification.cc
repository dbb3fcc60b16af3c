// Bench identification (body clamped, load cells present): c_T from load-cell
// force against telemetry, k and d from the clamped arm response to the
// measured force, and the static deflection-force map of each arm.
#include <ceres/ceres.h>

#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <sstream>
#include <string>

#include "identification/bench_residuals.h"
#include "identification/clamped_arm_residual.h"
#include "identification/deflection_force_map.h"
#include "identification/fit_support.h"
#include "identification/identify.h"
#include "identification/prior_residual.h"
#include "identification/thrust_residual.h"

namespace birotor {
namespace {

constexpr int64_t kMaxLoadCellGapUs = 5000;  // interpolate load cells over at most 5 ms
constexpr size_t kMaxPlotPoints = 2000;      // per plot panel

double LoadCellForce(const LoadCellSample& s, int rotor) { return s.force_n[rotor]; }

// Load-cell/telemetry pairs thrust_sample_spacing_s apart on the c_T ratio
// block (ThrustResidual, Huber loss), with their data for the plot (may be null).
std::vector<ceres::ResidualBlockId> AddThrustResiduals(const std::vector<SensorLog>& logs, const VehicleParams& base,
                                                       const IdentificationOptions& options, ceres::Problem* problem,
                                                       double* c_ratio, std::vector<double>* plot_omega,
                                                       std::vector<double>* plot_force) {
  std::vector<ceres::ResidualBlockId> blocks;
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
        sum_sq += std::pow(force - thrust_coeff_n_s2_rad2 * omega * omega, 2);
        ++count;
      }
    }
  }
  return count > 0 ? std::sqrt(sum_sq / count) : 0.0;
}

void IdentifyBenchThrust(const std::vector<SensorLog>& logs, const VehicleParams& base,
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
  c_t.determined = sigma[0].determined && c_t.sigma <= options.max_relative_sigma * std::abs(c_t.value);
  std::ostringstream note;
  note << blocks.size() << " load-cell/telemetry pairs " << options.thrust_sample_spacing_s
       << " s apart (turbulence averaged)";
  c_t.note = note.str();
  if (!c_t.determined) result->errors.push_back("c_T: not determined by the load-cell data (no thrust variation)");
  result->estimates.push_back(c_t);
  result->residuals.push_back(
      {"load cell (force - c_T omega^2)", "N", stats.count, stats.rms_whitened, 0.0, inflation});
  result->residuals.back().rms_si = ThrustResidualRmsN(logs, c_t.value);
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

namespace {

// Global parameters of the clamped-arm fit, each a one-scalar Ceres block.
enum BenchArmParameter : int {
  kBenchK = 0,        // k / k_scale
  kBenchD = 1,        // d / d_scale
  kBenchTipMass = 2,  // m_p / m_scale
  kBenchScale1 = 3,   // gauge scale arm 1 [1]
  kBenchScale2 = 4,   // gauge scale arm 2 [1]
  kBenchOffset1 = 5,  // gauge offset arm 1 / sigma_b
  kBenchOffset2 = 6,  // gauge offset arm 2 / sigma_b
};
constexpr int kBenchArmParameters = 7;

// Paired strain/load-cell samples of one arm of one log.
struct ArmData {
  int arm = 0;
  std::vector<int64_t> utime;
  std::vector<double> deflection_rad, force_n;
  std::vector<bool> valid;
};

// Strain samples of every (log, arm) with the load-cell force at the same
// time; the valid pairs also go to map_b, map_f (the static map's data).
std::vector<ArmData> CollectArmData(const std::vector<SensorLog>& logs, std::vector<double> map_b[2],
                                    std::vector<double> map_f[2]) {
  std::vector<ArmData> data;  // per (log, arm)
  for (const SensorLog& log : logs) {
    for (int arm = 0; arm < 2; ++arm) {
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

// One output-error window [begin, end) of data[data_index].
struct ArmWindow {
  size_t data_index, begin, end;
};

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

// Static line reading = a + c f of one arm by least squares (gauges.md:
// a = o_i - s_i sign_i L m_p g / k, c = s_i sign_i L / k).
struct StaticLine {
  double intercept_rad = 0.0;  // a
  double slope_rad_n = 0.0;    // c [rad/N]
};

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

// Sum of squared whitened residuals of the windows at the given parameters
// with each window's initial state chosen by linear least squares (the
// output is linear in (b_0, b_dot_0) up to the tiny cos(b) term): r(x) ~
// r(0) + J x with J from two unit responses. Used to scan the arm frequency
// before the fit, whose cost has local minima a few percent apart in k / m_p.
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

}  // namespace

void IdentifyBenchArms(const std::vector<SensorLog>& logs, const VehicleParams& base,
                       const IdentificationOptions& options, IdentificationResult* result) {
  const CalibrationFact& fact = options.calibration;
  const double L = base.arm_length_m, g = base.gravity_m_s2;
  const double sigma_b = options.strain_noise_rad;

  std::vector<double> map_b[2], map_f[2];
  const std::vector<ArmData> data = CollectArmData(logs, map_b, map_f);
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

  ParameterEstimate k = ParameterEstimate::Named("arm_stiffness_n_m_rad", "k");
  ParameterEstimate damping = ParameterEstimate::Named("arm_damping_n_m_s_rad", "d");
  ParameterEstimate tip_mass = ParameterEstimate::Named("tip_mass_kg", "m_p");
  ParameterEstimate scale[2], offset[2];
  for (int arm = 0; arm < 2; ++arm) {
    scale[arm].key = "gauge_scale[" + std::to_string(arm) + "]";
    scale[arm].symbol = "s_" + std::to_string(arm + 1);
    offset[arm].key = "gauge_offset_rad[" + std::to_string(arm) + "]";
    offset[arm].symbol = "o_" + std::to_string(arm + 1);
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
  std::ostringstream fact_text;
  if (weighed) {
    fact_text << "weighed tip mass m_p = " << fact.tip_mass_kg << " +- " << fact.tip_mass_std_kg
              << " kg; gauge scales identified";
  } else {
    fact_text << "factory gauge scale s = [" << base.gauge_scale[0] << ", " << base.gauge_scale[1] << "]";
    fact_text << (fact.gauge_scale_std > 0.0 ? " +- " + std::to_string(fact.gauge_scale_std) : " (held)");
    fact_text << "; tip mass identified";
  }
  if (weighed && fact.gauge_scale_std > 0.0) fact_text << " with the factory scale prior +- " << fact.gauge_scale_std;
  result->calibration_fact = fact_text.str();

  // Initial values from the statics: per arm c = s sign L / k, a = o - c m_p g.
  const StaticLine lines[2] = {FitStaticLine(map_f[0], map_b[0]), FitStaticLine(map_f[1], map_b[1])};
  ClampedArmWindowResidual::Scales scales;
  scales.stiffness_n_m_rad = base.arm_stiffness_n_m_rad;
  scales.damping_n_m_s_rad = base.arm_damping_n_m_s_rad > 0.0 ? base.arm_damping_n_m_s_rad : 0.1;
  scales.tip_mass_kg = base.tip_mass_kg;
  const double mp0 = weighed ? fact.tip_mass_kg : base.tip_mass_kg;
  double k0 = 0.0;
  for (int arm = 0; arm < 2; ++arm) {
    const double c = lines[arm].slope_rad_n * kArmSign[arm];
    k0 += 0.5 * (c > 0.0 ? base.gauge_scale[arm] * L / c : base.arm_stiffness_n_m_rad);
  }
  std::array<double, kBenchArmParameters> theta;
  auto set_statics = [&](double k_n_m_rad, double mp_kg, const double gauge_scale[2]) {
    theta[kBenchK] = k_n_m_rad / scales.stiffness_n_m_rad;
    theta[kBenchTipMass] = mp_kg / scales.tip_mass_kg;
    for (int arm = 0; arm < 2; ++arm) {
      theta[kBenchScale1 + arm] = gauge_scale[arm];
      const double c = kArmSign[arm] * gauge_scale[arm] * L / k_n_m_rad;  // slope implied by s_i, k
      theta[kBenchOffset1 + arm] = (lines[arm].intercept_rad + c * mp_kg * g) / sigma_b;
    }
  };
  theta[kBenchD] = base.arm_damping_n_m_s_rad / scales.damping_n_m_s_rad;
  set_statics(k0, mp0, base.gauge_scale);

  // Windows of every (log, arm).
  std::vector<std::unique_ptr<ClampedArmWindowResidual>> probes;  // for the frequency scan
  const std::vector<ArmWindow> windows = ArmWindows(data, options);
  auto window_samples = [&](const ArmWindow& w) { return ArmWindowSamples(data, w); };

  // Frequency scan: the ratio k / m_p over a factor 4 in 3 % steps on up to 24
  // windows, holding the static slope s_i / k. Scale held: m_p moves; scale
  // free: k and s_i move together (m_p is the weighed one).
  {
    constexpr size_t kScanWindows = 24;
    std::vector<ClampedArmWindowResidual*> scan;
    const size_t count = std::min(kScanWindows, windows.size());
    for (size_t w = 0; w < count; ++w) {
      const ArmWindow& spec = windows[(2 * w + 1) * windows.size() / (2 * count)];
      probes.push_back(std::make_unique<ClampedArmWindowResidual>(base, data[spec.data_index].arm, window_samples(spec),
                                                                  sigma_b, options.integration_substeps, scales,
                                                                  options.huber_threshold));
      scan.push_back(probes.back().get());
    }
    double best_cost = std::numeric_limits<double>::infinity(), best_q = 1.0;
    for (double q = 0.5; q <= 2.0; q *= 1.03) {
      if (scale_free && weighed) {
        const double gauge_scale[2] = {base.gauge_scale[0] * q, base.gauge_scale[1] * q};
        set_statics(k0 * q, mp0, gauge_scale);
      } else {
        set_statics(k0, mp0 / q, base.gauge_scale);
      }
      const double cost = CostWithBestInitialStates(scan, theta.data());
      if (cost < best_cost) {
        best_cost = cost;
        best_q = q;
      }
    }
    if (scale_free && weighed) {
      const double gauge_scale[2] = {base.gauge_scale[0] * best_q, base.gauge_scale[1] * best_q};
      set_statics(k0 * best_q, mp0, gauge_scale);
    } else {
      set_statics(k0, mp0 / best_q, base.gauge_scale);
    }
  }

  ceres::Problem problem;
  std::deque<std::array<double, 2>> states;
  std::vector<ceres::ResidualBlockId> blocks;
  double* p = theta.data();
  for (const ArmWindow& w : windows) {
    const ArmData& d = data[w.data_index];
    const int arm = d.arm;
    // Initial state: static deflection under the first force, at rest.
    const double reading_rad = lines[arm].intercept_rad + lines[arm].slope_rad_n * d.force_n[w.begin];
    states.push_back({(reading_rad - p[kBenchOffset1 + arm] * sigma_b) / p[kBenchScale1 + arm], 0.0});
    blocks.push_back(problem.AddResidualBlock(
        ClampedArmWindowResidual::Create(base, arm, window_samples(w), sigma_b, options.integration_substeps, scales,
                                         options.huber_threshold),
        nullptr, &p[kBenchK], &p[kBenchD], &p[kBenchTipMass], &p[kBenchScale1 + arm], &p[kBenchOffset1 + arm],
        states.back().data()));
  }
  problem.SetParameterLowerBound(&p[kBenchK], 0, 1e-3);
  problem.SetParameterLowerBound(&p[kBenchD], 0, 0.0);
  problem.SetParameterLowerBound(&p[kBenchTipMass], 0, 1e-3);
  if (!mass_free) problem.SetParameterBlockConstant(&p[kBenchTipMass]);
  if (weighed && fact.tip_mass_std_kg > 0.0) {
    problem.AddResidualBlock(
        PriorResidual::Create(fact.tip_mass_kg / scales.tip_mass_kg, fact.tip_mass_std_kg / scales.tip_mass_kg),
        nullptr, &p[kBenchTipMass]);
  }
  for (int arm = 0; arm < 2; ++arm) {
    double* s = &p[kBenchScale1 + arm];
    if (!problem.HasParameterBlock(s)) continue;
    problem.SetParameterLowerBound(s, 0, 0.1);
    if (!scale_free) {
      problem.SetParameterBlockConstant(s);
    } else if (fact.gauge_scale_std > 0.0) {
      problem.AddResidualBlock(PriorResidual::Create(base.gauge_scale[arm], fact.gauge_scale_std), nullptr, s);
    }
  }
  SolveProblem(options, &problem);
  const ResidualStatistics stats = ComputeResidualStatistics(&problem, blocks, 1, 0);
  const double inflation = VarianceInflation(stats);

  std::vector<double*> free_blocks;
  std::vector<int> free_index;
  for (int i = 0; i < kBenchArmParameters; ++i) {
    if (problem.HasParameterBlock(&p[i]) && !problem.IsParameterBlockConstant(&p[i])) {
      free_blocks.push_back(&p[i]);
      free_index.push_back(i);
    }
  }
  const std::vector<BlockSigma> sigma = ComputeBlockSigmas(&problem, free_blocks, inflation, options.num_threads);
  const double units[kBenchArmParameters] = {
      scales.stiffness_n_m_rad, scales.damping_n_m_s_rad, scales.tip_mass_kg, 1.0, 1.0, sigma_b, sigma_b};
  ParameterEstimate* estimates[kBenchArmParameters] = {&k,        &damping,   &tip_mass, &scale[0],
                                                       &scale[1], &offset[0], &offset[1]};
  const std::string note = "output error of the clamped arm over " + std::to_string(blocks.size()) + " windows";
  for (size_t n = 0; n < free_blocks.size(); ++n) {
    const int i = free_index[n];
    ParameterEstimate* e = estimates[i];
    e->value = p[i] * units[i];
    e->sigma = sigma[n].sigma * units[i];
    // An offset may be zero: judged against the strain noise instead.
    const double size = (i == kBenchOffset1 || i == kBenchOffset2) ? sigma_b : std::abs(e->value);
    e->determined = sigma[n].determined && e->sigma <= options.max_relative_sigma * size;
    e->note = note;
  }
  // Floors for what the sampled load-cell input cannot give better (options).
  auto add_floor = [](ParameterEstimate* e, double relative, const char* what) {
    if (!std::isfinite(e->value) || relative <= 0.0) return;
    e->sigma = std::hypot(e->sigma, relative * e->value);
    e->note += std::string("; sigma includes the ") + what;
  };
  add_floor(&damping, options.bench_damping_floor, "damping floor (bench_damping_floor)");
  if (mass_free && !weighed) {
    add_floor(&tip_mass, options.bench_frequency_floor, "frequency floor (bench_frequency_floor)");
    // The offsets follow m_p through the static intercept, o_i = a_i + s_i sign_i L m_p g / k.
    for (int arm = 0; arm < 2; ++arm) {
      const double floor_rad = options.bench_frequency_floor * p[kBenchScale1 + arm] * L * tip_mass.value * g / k.value;
      if (std::isfinite(offset[arm].value) && std::isfinite(floor_rad)) {
        offset[arm].sigma = std::hypot(offset[arm].sigma, floor_rad);
        offset[arm].note += "; sigma includes m_p's frequency floor through the static intercept";
      }
    }
  } else {
    add_floor(&k, options.bench_frequency_floor, "frequency floor (bench_frequency_floor)");
    for (int arm = 0; arm < 2; ++arm) {
      if (scale_free) add_floor(&scale[arm], options.bench_frequency_floor, "frequency floor (bench_frequency_floor)");
    }
  }
  if (stats.rms_whitened > options.misfit_rms_warn) {
    std::ostringstream warning;
    warning.precision(3);
    warning << "clamped-arm model misfit: strain residual RMS " << stats.rms_whitened
            << " sigma; every arm sigma widened by that factor (check the vehicle model and the strain noise)";
    result->warnings.push_back(warning.str());
    for (ParameterEstimate* e : estimates) e->note += "; widened for the model misfit";
  }
  {
    std::vector<std::string> names;
    std::vector<double> values, sigmas;
    for (const int i : free_index) {
      names.push_back(estimates[i]->symbol);
      values.push_back(estimates[i]->value);
      sigmas.push_back(estimates[i]->sigma);
    }
    const std::vector<std::vector<double>> rho = ComputeBlockCorrelations(&problem, free_blocks, options.num_threads);
    const std::vector<std::string> lines_text = DescribeCorrelations(rho, names, values, sigmas, 0.99);
    result->correlations.insert(result->correlations.end(), lines_text.begin(), lines_text.end());
  }
  if (!k.determined) result->errors.push_back("k: not determined by the bench strain data (no force variation)");
  if (!damping.determined) {
    result->warnings.push_back("d: not determined (the arm modes are barely excited); base value kept");
  }
  result->estimates.push_back(k);
  result->estimates.push_back(damping);
  if (mass_free) {
    if (!tip_mass.determined) {
      result->warnings.push_back("m_p: not determined by the bench data (arm modes not excited); base value kept");
    }
    result->estimates.push_back(tip_mass);
  }
  for (int arm = 0; arm < 2; ++arm) {
    if (scale_free) {
      if (!scale[arm].determined) result->errors.push_back(scale[arm].symbol + ": gauge scale not determined");
      result->estimates.push_back(scale[arm]);
    }
    if (!offset[arm].determined) result->errors.push_back(offset[arm].symbol + ": gauge offset not determined");
    result->estimates.push_back(offset[arm]);
  }
  result->residuals.push_back(
      {"strain (clamped arm model)", "rad", stats.count, stats.rms_whitened, stats.rms_whitened * sigma_b, inflation});
  if (k.determined) result->params.arm_stiffness_n_m_rad = k.value;
  if (damping.determined) result->params.arm_damping_n_m_s_rad = damping.value;
  if (mass_free && tip_mass.determined) result->params.tip_mass_kg = tip_mass.value;
  if (!mass_free) result->params.tip_mass_kg = fact.tip_mass_kg;
  for (int arm = 0; arm < 2; ++arm) {
    if (scale_free && scale[arm].determined) result->params.gauge_scale[arm] = scale[arm].value;
    if (offset[arm].determined) result->params.gauge_offset_rad[arm] = offset[arm].value;
  }
}

void AddBenchResiduals(const std::vector<SensorLog>& logs, const VehicleParams& bench,
                       const IdentificationOptions& options, ceres::Problem* problem, const SharedRatioBlocks& shared,
                       BenchResiduals* out) {
  out->thrust = AddThrustResiduals(logs, bench, options, problem, shared.thrust_coeff, nullptr, nullptr);
  std::vector<double> map_b[2], map_f[2];
  const std::vector<ArmData> data = CollectArmData(logs, map_b, map_f);
  const double sigma_b = options.strain_noise_rad;
  ClampedArmWindowResidual::Scales scales;
  scales.stiffness_n_m_rad = bench.arm_stiffness_n_m_rad;
  scales.damping_n_m_s_rad = bench.arm_damping_n_m_s_rad > 0.0 ? bench.arm_damping_n_m_s_rad : 0.1;
  scales.tip_mass_kg = bench.tip_mass_kg;
  for (int arm = 0; arm < 2; ++arm) {
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
  for (int arm = 0; arm < 2; ++arm) {
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
