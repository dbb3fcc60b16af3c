// Flight identification (no load cells): k, d and c_T from the free-flight
// arm dynamics driven by the motor model's rotor speeds, predicting deflections
// and, when the IMU is present, pitch rate and specific force.
#include <ceres/ceres.h>

#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <string>

#include "identification/bench_residuals.h"
#include "identification/fit_support.h"
#include "identification/free_arm_residual.h"
#include "identification/identify.h"
#include "model/plant.h"

namespace birotor {
namespace {

constexpr int64_t kMaxMotorGapUs = 10000;  // interpolate telemetry over at most 10 ms
constexpr int64_t kMaxImuGapUs = 5000;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Relative cost change that ends the first solve (knots held: only a start
// for the second) and the final one: on flight_id the parameters move by
// less than 0.02 sigma after it, and the whole fit takes a third of the time
// of a 1e-10 tolerance.
constexpr double kStartTolerance = 1e-3;
constexpr double kFinalTolerance = 1e-6;
constexpr double kMotorSettleTimeConstants = 6.0;  // model speed trusted after 6 tau_m (0.25 % of the start error)

// Rotor speeds of the first-order motor model driven by the recorded
// commands (ZOH), at every motor sample: omega_{j+1} = MotorStep(omega_j,
// cmd_j, tau_m, dt). Telemetry noise (5 rad/s, white at 500 Hz) would
// otherwise drive the model arm modes with about 0.3 N of broadband force
// noise that the real, smooth rotor speed does not have. The model starts
// from the telemetry (or the command when there is none) after every gap and
// is marked settled kMotorSettleTimeConstants tau_m later.
struct ModelSpeeds {
  std::vector<double> omega_rad_s[2];
  std::vector<bool> settled;
};

ModelSpeeds ModelRotorSpeeds(const std::vector<MotorSample>& motor, const VehicleParams& params) {
  const double tau_s = params.motor_time_constant_s;
  const int64_t settle_us = static_cast<int64_t>(kMotorSettleTimeConstants * tau_s * 1e6);
  ModelSpeeds out;
  out.omega_rad_s[0].assign(motor.size(), kNaN);
  out.omega_rad_s[1].assign(motor.size(), kNaN);
  out.settled.assign(motor.size(), false);
  int64_t start_us = 0;
  for (size_t j = 0; j < motor.size(); ++j) {
    const MotorSample& m = motor[j];
    const bool commands_ok = std::isfinite(m.omega_cmd_rad_s[0]) && std::isfinite(m.omega_cmd_rad_s[1]);
    const bool continues = j > 0 && std::isfinite(out.omega_rad_s[0][j - 1]) &&
                           m.utime - motor[j - 1].utime <= kMaxMotorGapUs && m.utime > motor[j - 1].utime;
    if (!commands_ok) continue;
    if (!continues) start_us = m.utime;
    for (int rotor = 0; rotor < 2; ++rotor) {
      double omega;
      if (continues) {
        omega = MotorStep(out.omega_rad_s[rotor][j - 1], ClampCommand(params, motor[j - 1].omega_cmd_rad_s[rotor]),
                          tau_s, 1e-6 * static_cast<double>(m.utime - motor[j - 1].utime));
      } else {
        omega = std::isfinite(m.omega_meas_rad_s[rotor]) ? m.omega_meas_rad_s[rotor]
                                                         : ClampCommand(params, m.omega_cmd_rad_s[rotor]);
      }
      out.omega_rad_s[rotor][j] = omega;
    }
    out.settled[j] = m.utime - start_us >= settle_us;
  }
  return out;
}

}  // namespace

void IdentifyFlightArms(const std::vector<SensorLog>& logs, const VehicleParams& base,
                        const IdentificationOptions& options, IdentificationResult* result,
                        const std::vector<SensorLog>* bench_logs) {
  const bool joint = bench_logs != nullptr && !bench_logs->empty();
  FreeArmWindowResidual::Scales scales;
  scales.stiffness_n_m_rad = base.arm_stiffness_n_m_rad;
  scales.damping_n_m_s_rad = base.arm_damping_n_m_s_rad > 0.0 ? base.arm_damping_n_m_s_rad : 0.1;
  scales.thrust_coeff_n_s2_rad2 = base.thrust_coeff_n_s2_rad2;
  scales.tip_mass_kg = base.tip_mass_kg;
  FreeArmWindowResidual::Noise noise{options.strain_noise_rad, options.gyro_noise_rad_s, options.accel_noise_m_s2,
                                     options.huber_threshold};

  // The motor time constant identified just before (IdentifyMotorTimeConstant), else the base value.
  const VehicleParams& motor_params = result->params;
  ceres::Problem problem;
  double k_ratio = 1.0;
  double d_ratio = base.arm_damping_n_m_s_rad / scales.damping_n_m_s_rad;
  double c_ratio = 1.0;
  double m_ratio = 1.0;
  // Candidate windows over every log, then at most flight_max_windows of
  // them spread evenly (the arm modes ring after every manoeuvre, so a
  // subset carries nearly all the information at a fraction of the cost).
  struct Window {
    size_t log, begin, end;
  };
  std::vector<std::vector<int64_t>> utimes(logs.size());
  std::vector<std::vector<FreeArmWindowResidual::Sample>> all_samples(logs.size());
  std::vector<Window> candidates;
  bool any_imu = false;
  for (size_t l = 0; l < logs.size(); ++l) {
    const SensorLog& log = logs[l];
    const bool use_imu = options.use_imu && !log.imu.empty();
    any_imu = any_imu || use_imu;
    const size_t n = log.strain.size();
    std::vector<int64_t>& utime = utimes[l];
    utime.resize(n);
    std::vector<bool> valid(n);
    std::vector<FreeArmWindowResidual::Sample>& all = all_samples[l];
    all.resize(n);
    const ModelSpeeds speeds = ModelRotorSpeeds(log.motor, motor_params);
    size_t motor_hint = 0, imu_hint = 0;
    for (size_t i = 0; i < n; ++i) {
      const StrainSample& s = log.strain[i];
      utime[i] = s.utime;
      FreeArmWindowResidual::Sample& out = all[i];
      // Deflections through the base file's gauge calibration (gauges.md:
      // b = (b_meas - o_i) / s_i; a bench identification gives s_i and o_i).
      for (int arm = 0; arm < 2; ++arm) {
        out.deflection_rad[arm] = (s.deflection_rad[arm] - base.gauge_offset_rad[arm]) / base.gauge_scale[arm];
      }
      bool ok = std::isfinite(s.deflection_rad[0]) && std::isfinite(s.deflection_rad[1]);
      // Exact ZOH motor response from the last motor sample at or before t.
      while (motor_hint + 1 < log.motor.size() && log.motor[motor_hint + 1].utime <= s.utime) ++motor_hint;
      const bool motor_ok = !log.motor.empty() && log.motor[motor_hint].utime <= s.utime &&
                            s.utime - log.motor[motor_hint].utime <= kMaxMotorGapUs && speeds.settled[motor_hint];
      ok = ok && motor_ok;
      for (int rotor = 0; rotor < 2 && ok; ++rotor) {
        const MotorSample& m = log.motor[motor_hint];
        out.omega_rad_s[rotor] =
            MotorStep(speeds.omega_rad_s[rotor][motor_hint], ClampCommand(motor_params, m.omega_cmd_rad_s[rotor]),
                      motor_params.motor_time_constant_s, 1e-6 * static_cast<double>(s.utime - m.utime));
        ok = std::isfinite(out.omega_rad_s[rotor]);
      }
      out.gyro_rad_s = out.accel_m_s2[0] = out.accel_m_s2[1] = kNaN;
      if (use_imu) {
        size_t h0 = imu_hint, h1 = imu_hint, h2 = imu_hint;
        double g = kNaN, ax = kNaN, az = kNaN;
        if (InterpolateAt(
                log.imu, s.utime, kMaxImuGapUs, &h0, [](const ImuSample& m) { return m.gyro_y_rad_s; }, &g) &&
            InterpolateAt(
                log.imu, s.utime, kMaxImuGapUs, &h1, [](const ImuSample& m) { return m.accel_x_m_s2; }, &ax) &&
            InterpolateAt(
                log.imu, s.utime, kMaxImuGapUs, &h2, [](const ImuSample& m) { return m.accel_z_m_s2; }, &az)) {
          out.gyro_rad_s = g;
          out.accel_m_s2[0] = ax;
          out.accel_m_s2[1] = az;
        }
        imu_hint = h0;
      }
      valid[i] = ok;
    }
    const int64_t max_gap_us = 3 * std::max<int64_t>(MedianIntervalUs(utime), 1);
    for (const auto& [begin, end] : ContiguousWindows(utime, valid, options.flight_window_s, max_gap_us, 20)) {
      candidates.push_back({l, begin, end});
    }
  }
  std::vector<Window> windows = candidates;
  const size_t max_windows = static_cast<size_t>(options.flight_max_windows);
  if (max_windows > 0 && candidates.size() > max_windows) {
    windows.clear();
    for (size_t w = 0; w < max_windows; ++w) {
      windows.push_back(candidates[(2 * w + 1) * candidates.size() / (2 * max_windows)]);
    }
  }
  // Rotor turbulence knots (FreeArmWindowResidual): only when the base file
  // gives the vehicle a turbulence to model.
  const bool model_turbulence =
      options.flight_turbulence_knot_s > 0.0 && base.turbulence_std > 0.0 && base.turbulence_corr_time_s > 0.0;
  const double knot_s = model_turbulence ? options.flight_turbulence_knot_s : 0.0;
  // Per window: x_0 and the knots [eta_1 knots, eta_2 knots] (may be empty).
  std::deque<std::array<double, kFreeArmStateSize>> states;
  std::deque<std::vector<double>> knots;
  std::vector<ceres::ResidualBlockId> blocks;
  std::vector<const FreeArmWindowResidual*> functors;
  for (const Window& w : windows) {
    const std::vector<int64_t>& utime = utimes[w.log];
    std::vector<FreeArmWindowResidual::Sample> samples(all_samples[w.log].begin() + w.begin,
                                                       all_samples[w.log].begin() + w.end);
    for (size_t i = 0; i + 1 < samples.size(); ++i) {
      samples[i].dt_s = 1e-6 * static_cast<double>(utime[w.begin + i + 1] - utime[w.begin + i]);
    }
    samples.back().dt_s = 0.0;
    // Initial state: measured pitch rate and deflections; deflection rates
    // from a least-squares line through the first samples (strain noise
    // 2e-5 rad gives a few mrad/s), so the solver starts near the optimum.
    // Turbulence knots start at 0 (its mean).
    const FreeArmWindowResidual::Sample& first = samples.front();
    std::array<double, kFreeArmStateSize> x0 = {std::isfinite(first.gyro_rad_s) ? first.gyro_rad_s : 0.0,
                                                first.deflection_rad[0], first.deflection_rad[1], 0.0, 0.0};
    const size_t fit_n = std::min<size_t>(samples.size(), 5);
    for (int arm = 0; arm < 2; ++arm) {
      double st = 0.0, sb = 0.0, stt = 0.0, stb = 0.0, t = 0.0;
      for (size_t i = 0; i < fit_n; ++i) {
        st += t;
        sb += samples[i].deflection_rad[arm];
        stt += t * t;
        stb += t * samples[i].deflection_rad[arm];
        t += samples[i].dt_s;
      }
      const double det = fit_n * stt - st * st;
      if (det > 0.0) x0[arm == 0 ? kFreeB1Dot : kFreeB2Dot] = (fit_n * stb - st * sb) / det;
    }
    const FreeArmWindowResidual* functor = nullptr;
    ceres::CostFunction* cost = FreeArmWindowResidual::Create(
        base, std::move(samples), noise, options.flight_integration_substeps, scales, knot_s, &functor);
    states.push_back(x0);
    std::vector<double>& window_knots = knots.emplace_back(functor->KnotBlockSize(), 0.0);
    std::vector<double*> parameters = {&k_ratio, &d_ratio, &c_ratio, &m_ratio, states.back().data()};
    if (!window_knots.empty()) parameters.push_back(window_knots.data());
    blocks.push_back(problem.AddResidualBlock(cost, nullptr, parameters));
    if (ceres::CostFunction* prior = functor->TurbulencePrior(base.turbulence_std, base.turbulence_corr_time_s)) {
      problem.AddResidualBlock(prior, nullptr, window_knots.data());
    }
    functors.push_back(functor);
  }
  ParameterEstimate k = ParameterEstimate::Named("arm_stiffness_n_m_rad", "k");
  ParameterEstimate damping = ParameterEstimate::Named("arm_damping_n_m_s_rad", "d");
  ParameterEstimate c_t = ParameterEstimate::Named("thrust_coeff_n_s2_rad2", "c_T");
  ParameterEstimate tip_mass = ParameterEstimate::Named("tip_mass_kg", "m_p");
  if (blocks.empty()) {
    result->errors.push_back("k, d, c_T: no STRAIN samples with MOTOR telemetry (omega_meas) at the same time");
    result->estimates.insert(result->estimates.end(), {k, damping, c_t});
    return;
  }
  problem.SetParameterLowerBound(&k_ratio, 0, 1e-3);
  problem.SetParameterLowerBound(&c_ratio, 0, 1e-3);
  problem.SetParameterLowerBound(&d_ratio, 0, 0.0);
  problem.SetParameterLowerBound(&m_ratio, 0, 1e-3);
  // Joint fit: the bench residuals on the same blocks; the bench
  // determines d and m_p, so both are free whatever the flight options say.
  BenchResiduals bench;
  if (joint) {
    AddBenchResiduals(*bench_logs, base, options, &problem, {&k_ratio, &d_ratio, &c_ratio, &m_ratio}, &bench);
  } else {
    if (!options.flight_fit_damping) problem.SetParameterBlockConstant(&d_ratio);
    if (!options.flight_fit_tip_mass) problem.SetParameterBlockConstant(&m_ratio);
  }
  // Two stages: the turbulence knots held at 0 first (the initial states and
  // the vehicle parameters then converge in a few iterations), then free.
  // Started at once from zero turbulence, the Huber-weighted misfit of the
  // whole 1 % thrust noise keeps the trust region small for ~20 iterations.
  if (model_turbulence) {
    for (std::vector<double>& window_knots : knots) problem.SetParameterBlockConstant(window_knots.data());
    SolveProblem(options, &problem, kStartTolerance);
    for (std::vector<double>& window_knots : knots) problem.SetParameterBlockVariable(window_knots.data());
  }
  SolveProblem(options, &problem, kFinalTolerance);

  // Strain residuals carry the unmodelled turbulence (correlated over ~0.1 s):
  // the inflation from their autocorrelation keeps the covariance honest.
  double inflation = 1.0;
  const char* names[kFreeArmResidualsPerSample] = {"strain arm 1 (free-flight model)",
                                                   "strain arm 2 (free-flight model)", "gyro pitch rate",
                                                   "accelerometer x", "accelerometer z"};
  const char* units[kFreeArmResidualsPerSample] = {"rad", "rad", "rad/s", "m/s^2", "m/s^2"};
  const double sigmas[kFreeArmResidualsPerSample] = {options.strain_noise_rad, options.strain_noise_rad,
                                                     options.gyro_noise_rad_s, options.accel_noise_m_s2,
                                                     options.accel_noise_m_s2};
  for (int channel = 0; channel < kFreeArmResidualsPerSample; ++channel) {
    if (channel >= kResGyro && !any_imu) continue;
    const ResidualStatistics stats = ComputeResidualStatistics(&problem, blocks, kFreeArmResidualsPerSample, channel);
    if (stats.count == 0) continue;
    const double channel_inflation = VarianceInflation(stats);
    inflation = std::max(inflation, channel_inflation);
    result->residuals.push_back({names[channel], units[channel], stats.count, stats.rms_whitened,
                                 stats.rms_whitened * sigmas[channel], channel_inflation});
  }
  std::vector<ceres::ResidualBlockId> clusters = blocks;
  if (joint) {
    // The bench blocks: each load-cell pair and each clamped-arm window is
    // a cluster of the sandwich too; the flight channels' inflation is not
    // applied to what the bench determines.
    inflation = 1.0;
    clusters.insert(clusters.end(), bench.thrust.begin(), bench.thrust.end());
    clusters.insert(clusters.end(), bench.arms.begin(), bench.arms.end());
    const ResidualStatistics thrust = ComputeResidualStatistics(&problem, bench.thrust, 1, 0);
    const ResidualStatistics arms = ComputeResidualStatistics(&problem, bench.arms, 1, 0);
    result->residuals.push_back({"load cell (force - c_T omega^2), joint fit", "N", thrust.count, thrust.rms_whitened,
                                 ThrustResidualRmsN(*bench_logs, c_ratio * scales.thrust_coeff_n_s2_rad2),
                                 VarianceInflation(thrust)});
    result->residuals.push_back({"strain (clamped arm model), joint fit", "rad", arms.count, arms.rms_whitened,
                                 arms.rms_whitened * options.strain_noise_rad, VarianceInflation(arms)});
  }
  const std::vector<double*> shared = {&k_ratio, &d_ratio, &c_ratio, &m_ratio};
  Eigen::MatrixXd covariance;
  std::vector<BlockSigma> sigma = ComputeBlockSigmas(&problem, shared, inflation, options.num_threads, &covariance);
  // The inflation above assumes one correlation time for the whole misfit;
  // what is left of the turbulence between the knots is correlated across
  // channels and windows' parameters alike. The windows themselves are
  // independent (1.5 s apart on flight_id, 15 turbulence correlation times),
  // so their scatter bounds the sigma from below (sandwich estimate).
  const std::vector<double> robust =
      ComputeClusterRobustSigmas(&problem, shared, covariance, clusters, options.num_threads);
  for (size_t i = 0; i < robust.size(); ++i) sigma[i].sigma = std::max(sigma[i].sigma, robust[i]);
  std::string note = "output error of the free-flight arm model over " + std::to_string(blocks.size()) + " of " +
                     std::to_string(candidates.size()) + " windows" + (any_imu ? " with IMU" : " without IMU");
  if (joint) {
    note = "joint fit (one problem): " + std::to_string(bench.thrust.size()) + " load-cell pairs, " +
           std::to_string(bench.arms.size()) + " clamped-arm windows and " + note;
  }
  auto fill = [&](ParameterEstimate* e, double ratio, double scale, const BlockSigma& s) {
    e->value = ratio * scale;
    e->sigma = s.sigma * scale;
    e->determined = s.determined && e->sigma <= options.max_relative_sigma * std::abs(e->value);
    e->note = note;
  };
  fill(&k, k_ratio, scales.stiffness_n_m_rad, sigma[0]);
  fill(&damping, d_ratio, scales.damping_n_m_s_rad, sigma[1]);
  fill(&c_t, c_ratio, scales.thrust_coeff_n_s2_rad2, sigma[2]);
  fill(&tip_mass, m_ratio, scales.tip_mass_kg, sigma[3]);
  if (!k.determined) result->errors.push_back("k: not determined by the flight data (arm dynamics not excited)");
  if (!c_t.determined) {
    result->errors.push_back(std::string("c_T: not determined by the flight data") +
                             (any_imu ? "" : " (no IMU: only c_T / k is seen by the strain gauges)"));
  }
  if (joint) {
    // The bench floors (options): what the 1 kHz load-cell input cannot give better.
    damping.sigma = std::hypot(damping.sigma, options.bench_damping_floor * damping.value);
    ParameterEstimate& floored = options.calibration.TipMassWeighed() ? k : tip_mass;
    floored.sigma = std::hypot(floored.sigma, options.bench_frequency_floor * floored.value);
    damping.note += "; sigma includes bench_damping_floor";
    floored.note += "; sigma includes bench_frequency_floor";
  } else {
    // A flight reads its deflections through the base file's gauge scales:
    // a relative scale error delta moves k by -delta (statics, b = f L / k)
    // and m_p with it (the arm frequency fixes k / m_p); c_T comes from the
    // accelerometer against the rotor speeds and does not move. What the
    // flight determines is k / s and m_p / s.
    const double scale = 0.5 * (base.gauge_scale[0] + base.gauge_scale[1]);
    const double relative = options.calibration.gauge_scale_std / scale;
    for (ParameterEstimate* e : {&k, &tip_mass}) {
      if (relative > 0.0) {
        e->sigma = std::hypot(e->sigma, relative * e->value);
        e->note += "; sigma includes the gauge scale's (--gauge-scale-std)";
      } else {
        e->note +=
            "; relative to the base file's gauge_scale (the flight determines it over s_i; "
            "--gauge-scale-std adds the scale's uncertainty)";
      }
    }
  }
  if (!joint && !options.flight_fit_damping) {
    damping.determined = false;
    damping.sigma = kNaN;
    damping.note = "held at the base value (flight_fit_damping is off: flight data barely constrain d)";
  }
  if (!damping.determined) result->warnings.push_back("d: not determined by the flight data; base value kept");
  // Fit versus data: measured and predicted deflections over two windows,
  // at one third and two thirds of the data.
  for (size_t n = 1; n <= 2 && n < functors.size(); ++n) {
    const size_t w = n * functors.size() / 3;
    const FreeArmWindowResidual& f = *functors[w];
    const std::vector<FreeArmState<double>> predicted =
        f.Predict(k_ratio, d_ratio, c_ratio, m_ratio, states[w].data(), knots[w].empty() ? nullptr : knots[w].data());
    for (int arm = 0; arm < 2; ++arm) {
      FitPlot plot;
      plot.title = "free flight, window " + std::to_string(w + 1) + " of " + std::to_string(functors.size()) +
                   ": arm " + std::to_string(arm + 1) + " deflection";
      plot.x_label = "time in window [s]";
      plot.y_label = "b" + std::to_string(arm + 1) + " [mrad]";
      double t_s = 0.0;
      for (size_t j = 0; j < predicted.size(); ++j) {
        plot.x.push_back(t_s);
        plot.data.push_back(1e3 * f.samples()[j].deflection_rad[arm]);
        plot.model.push_back(1e3 * predicted[j](arm == 0 ? kFreeB1 : kFreeB2));
        t_s += f.samples()[j].dt_s;
      }
      result->plots.push_back(std::move(plot));
    }
  }
  result->estimates.insert(result->estimates.end(), {k, damping, c_t});
  if (options.flight_fit_tip_mass || joint) {
    if (!tip_mass.determined) {
      result->warnings.push_back("m_p: not determined by the flight data; base value kept");
    }
    result->estimates.push_back(tip_mass);
    if (tip_mass.determined) result->params.tip_mass_kg = tip_mass.value;
  }
  if (k.determined) result->params.arm_stiffness_n_m_rad = k.value;
  if (damping.determined) result->params.arm_damping_n_m_s_rad = damping.value;
  if (c_t.determined) result->params.thrust_coeff_n_s2_rad2 = c_t.value;
}

}  // namespace birotor
