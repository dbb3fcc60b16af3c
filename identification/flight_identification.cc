// Flight identification (no load cells): k, d and c_T from the free-flight
// arm dynamics driven by the motor model's rotor speeds, predicting deflections
// and, when the IMU is present, pitch rate and specific force.
#include <ceres/ceres.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>
#include <string>

#include "identification/fit_stages.h"
#include "identification/fit_support.h"
#include "identification/flight_fit.h"
#include "identification/free_arm_window_cost.h"
#include "identification/identify.h"
#include "model/plant.h"
#include "samples/rotor_count.h"

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
  std::vector<double> omega_rad_s[kBirotorRotors];
  std::vector<bool> settled;
};

ModelSpeeds ModelRotorSpeeds(const std::vector<MotorSample>& motor, const BirotorParams& params) {
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
    for (int rotor = 0; rotor < kBirotorRotors; ++rotor) {
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

FlightSamples CollectFlightSamples(const std::vector<SensorLog>& logs, const BirotorParams& base,
                                   const BirotorParams& motor_params, const IdentificationOptions& options) {
  FlightSamples data;
  data.utime.resize(logs.size());
  data.samples.resize(logs.size());
  for (size_t l = 0; l < logs.size(); ++l) {
    const SensorLog& log = logs[l];
    const bool use_imu = options.use_imu && !log.imu.empty();
    data.any_imu = data.any_imu || use_imu;
    const size_t n = log.strain.size();
    std::vector<int64_t>& utime = data.utime[l];
    utime.resize(n);
    std::vector<bool> valid(n);
    std::vector<FreeArmWindowResidual::Sample>& all = data.samples[l];
    all.resize(n);
    const ModelSpeeds speeds = ModelRotorSpeeds(log.motor, motor_params);
    size_t motor_hint = 0, imu_hint = 0;
    for (size_t i = 0; i < n; ++i) {
      const StrainSample& s = log.strain[i];
      utime[i] = s.utime;
      FreeArmWindowResidual::Sample& out = all[i];
      // Deflections through the base file's gauge calibration (gauges.md:
      // b = (b_meas - o_i) / s_i; a bench identification gives s_i and o_i).
      for (int arm = 0; arm < kBirotorRotors; ++arm) {
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
      data.candidates.push_back({l, begin, end});
    }
  }
  return data;
}

std::vector<FlightWindow> SelectFlightWindows(const std::vector<FlightWindow>& candidates, int max_windows) {
  const size_t max_n = static_cast<size_t>(std::max(0, max_windows));
  if (max_n == 0 || candidates.size() <= max_n) return candidates;
  std::vector<FlightWindow> windows;
  for (size_t w = 0; w < max_n; ++w) windows.push_back(candidates[(2 * w + 1) * candidates.size() / (2 * max_n)]);
  return windows;
}

std::array<double, kFreeArmStateSize> InitialWindowState(const std::vector<FreeArmWindowResidual::Sample>& samples) {
  const FreeArmWindowResidual::Sample& first = samples.front();
  std::array<double, kFreeArmStateSize> x0 = {std::isfinite(first.gyro_rad_s) ? first.gyro_rad_s : 0.0,
                                              first.deflection_rad[0], first.deflection_rad[1], 0.0, 0.0};
  const size_t fit_n = std::min<size_t>(samples.size(), 5);
  for (int arm = 0; arm < kBirotorRotors; ++arm) {
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
  return x0;
}

void BuildFlightProblem(const FlightSamples& data, const std::vector<FlightWindow>& windows, const BirotorParams& base,
                        const IdentificationOptions& options, const std::vector<SensorLog>* bench_logs,
                        FlightProblem* fit) {
  fit->joint = bench_logs != nullptr && !bench_logs->empty();
  FreeArmWindowResidual::Scales& scales = fit->scales;
  scales.stiffness_n_m_rad = base.arm_stiffness_n_m_rad;
  scales.damping_n_m_s_rad = base.arm_damping_n_m_s_rad > 0.0 ? base.arm_damping_n_m_s_rad : 0.1;
  scales.thrust_coeff_n_s2_rad2 = base.thrust_coeff_n_s2_rad2;
  scales.tip_mass_kg = base.tip_mass_kg;
  fit->ratio = {1.0, base.arm_damping_n_m_s_rad / scales.damping_n_m_s_rad, 1.0, 1.0};
  const FreeArmWindowResidual::Noise noise{options.strain_noise_rad, options.gyro_noise_rad_s, options.accel_noise_m_s2,
                                           options.huber_threshold};
  // Rotor turbulence knots (FreeArmWindowResidual): only when the base file
  // gives the vehicle a turbulence to model.
  fit->model_turbulence =
      options.flight_turbulence_knot_s > 0.0 && base.turbulence_std > 0.0 && base.turbulence_corr_time_s > 0.0;
  fit->turbulence_std = base.turbulence_std;
  fit->turbulence_corr_time_s = base.turbulence_corr_time_s;
  const double knot_s = fit->model_turbulence ? options.flight_turbulence_knot_s : 0.0;
  ceres::Problem& problem = fit->problem;
  // The start problem (flight-only fits with turbulence knots): the same
  // windows and priors without the Huber weighting, over the same blocks.
  const bool quadratic_start = !fit->joint && fit->model_turbulence;
  if (quadratic_start) fit->start = std::make_unique<ceres::Problem>();
  FreeArmWindowResidual::Noise quadratic_noise = noise;
  quadratic_noise.huber = 0.0;
  for (const FlightWindow& w : windows) {
    const std::vector<int64_t>& utime = data.utime[w.log];
    std::vector<FreeArmWindowResidual::Sample> samples(data.samples[w.log].begin() + w.begin,
                                                       data.samples[w.log].begin() + w.end);
    for (size_t i = 0; i + 1 < samples.size(); ++i) {
      samples[i].dt_s = 1e-6 * static_cast<double>(utime[w.begin + i + 1] - utime[w.begin + i]);
    }
    samples.back().dt_s = 0.0;
    // Turbulence knots start at 0 (its mean).
    fit->states.push_back(InitialWindowState(samples));
    const FreeArmWindowResidual* functor = nullptr;
    ceres::CostFunction* quadratic =
        quadratic_start ? FreeArmWindowCost::Create(base, samples, quadratic_noise, options.flight_integration_substeps,
                                                    scales, knot_s)
                        : nullptr;
    ceres::CostFunction* cost = FreeArmWindowCost::Create(
        base, std::move(samples), noise, options.flight_integration_substeps, scales, knot_s, &functor);
    std::vector<double>& window_knots = fit->knots.emplace_back(functor->KnotBlockSize(), 0.0);
    std::vector<double*> parameters = fit->Blocks();
    parameters.push_back(fit->states.back().data());
    if (!window_knots.empty()) parameters.push_back(window_knots.data());
    fit->windows.push_back(problem.AddResidualBlock(cost, nullptr, parameters));
    ceres::CostFunction* prior = functor->TurbulencePrior(base.turbulence_std, base.turbulence_corr_time_s);
    fit->priors.push_back(prior != nullptr ? problem.AddResidualBlock(prior, nullptr, window_knots.data()) : nullptr);
    fit->functors.push_back(functor);
    if (quadratic_start) {
      fit->start->AddResidualBlock(quadratic, nullptr, parameters);
      if (prior != nullptr) {
        fit->start->AddResidualBlock(functor->TurbulencePrior(base.turbulence_std, base.turbulence_corr_time_s),
                                     nullptr, window_knots.data());
      }
    }
  }
  if (fit->windows.empty()) return;
  for (ceres::Problem* p : {&problem, fit->start.get()}) {
    if (p == nullptr) continue;
    for (const int i : {kFlightK, kFlightThrust, kFlightTipMass}) p->SetParameterLowerBound(&fit->ratio[i], 0, 1e-3);
    p->SetParameterLowerBound(&fit->ratio[kFlightD], 0, 0.0);
  }
  // Joint fit: the bench residuals on the same blocks; the bench
  // determines d and m_p, so both are free whatever the flight options say.
  if (fit->joint) {
    AddBenchResiduals(
        *bench_logs, base, options, &problem,
        {&fit->ratio[kFlightK], &fit->ratio[kFlightD], &fit->ratio[kFlightThrust], &fit->ratio[kFlightTipMass]},
        &fit->bench);
  } else {
    if (!options.flight_fit_damping) problem.SetParameterBlockConstant(&fit->ratio[kFlightD]);
    if (!options.flight_fit_tip_mass) problem.SetParameterBlockConstant(&fit->ratio[kFlightTipMass]);
  }
}

void SolveFlightProblem(const IdentificationOptions& options, FlightProblem* fit, double fraction) {
  FitProgress at{"flight: solve, start", static_cast<int>(fit->windows.size()), 0, fraction};
  if (fit->start != nullptr) {
    // The start without the Huber weighting: nearly linear in the states and
    // knots, it converges in a few Gauss-Newton steps (gentle 15 s: 4, where
    // from zero turbulence the Huber-weighted misfit of the whole 1 % thrust
    // noise, linear in |r|, kept the steps at 0.4 of their prediction for 22
    // iterations); the ratio blocks held or free as in the problem itself.
    for (double* block : fit->Blocks()) {
      if (fit->problem.IsParameterBlockConstant(block)) {
        fit->start->SetParameterBlockConstant(block);
      } else {
        fit->start->SetParameterBlockVariable(block);
      }
    }
    SolveProblem(options, fit->start.get(), kStartTolerance, &at);
    at.fraction += 0.05;
  } else if (fit->model_turbulence) {
    // Joint fits: the turbulence knots held at 0 first (the initial states
    // and the vehicle parameters then converge in a few iterations), then free.
    for (std::vector<double>& window_knots : fit->knots) fit->problem.SetParameterBlockConstant(window_knots.data());
    SolveProblem(options, &fit->problem, kStartTolerance, &at);
    for (std::vector<double>& window_knots : fit->knots) fit->problem.SetParameterBlockVariable(window_knots.data());
    at.fraction += 0.05;
  }
  at.stage = "flight: solve";
  SolveProblem(options, &fit->problem, kFinalTolerance, &at);
}

void ResolveFlightProblem(const IdentificationOptions& options, FlightProblem* fit, double fraction) {
  const FitProgress at{"flight: solve, m_p free", static_cast<int>(fit->windows.size()), 0, fraction};
  SolveProblem(options, &fit->problem, kFinalTolerance, &at);
}

std::vector<BlockSigma> FlightSigmas(const IdentificationOptions& options, bool any_imu,
                                     const std::vector<SensorLog>* bench_logs, FlightProblem* fit,
                                     std::vector<ResidualSummary>* residuals) {
  ceres::Problem* problem = &fit->problem;
  // Strain residuals carry the unmodelled turbulence (correlated over ~0.1 s):
  // the inflation from their autocorrelation keeps the covariance honest.
  double inflation = 1.0;
  const ResidualBlock blocks[kFreeArmResidualsPerSample] = {
      ResidualBlock::kFreeFlightStrain1, ResidualBlock::kFreeFlightStrain2, ResidualBlock::kGyroPitchRate,
      ResidualBlock::kAccelerometerX, ResidualBlock::kAccelerometerZ};
  const double sigmas[kFreeArmResidualsPerSample] = {options.strain_noise_rad, options.strain_noise_rad,
                                                     options.gyro_noise_rad_s, options.accel_noise_m_s2,
                                                     options.accel_noise_m_s2};
  for (int channel = 0; channel < kFreeArmResidualsPerSample; ++channel) {
    if (channel >= kResGyro && !any_imu) continue;
    const ResidualStatistics stats =
        ComputeResidualStatistics(problem, fit->windows, kFreeArmResidualsPerSample, channel);
    if (stats.count == 0) continue;
    const double channel_inflation = VarianceInflation(stats);
    inflation = std::max(inflation, channel_inflation);
    residuals->push_back(
        {blocks[channel], stats.count, stats.rms_whitened, stats.rms_whitened * sigmas[channel], channel_inflation});
  }
  // The inflation above assumes one correlation time for the whole misfit;
  // what is left of the turbulence between the knots is correlated across
  // channels and windows' parameters alike. The windows themselves are
  // independent (1.5 s apart on flight_id, 15 turbulence correlation times),
  // so their scatter bounds the sigma from below (sandwich estimate).
  std::vector<ceres::ResidualBlockId> clusters = fit->windows;
  if (fit->joint) {
    // The bench blocks: each load-cell pair and each clamped-arm window is
    // a cluster of the sandwich too; the flight channels' inflation is not
    // applied to what the bench determines.
    inflation = 1.0;
    const BenchResiduals& bench = fit->bench;
    clusters.insert(clusters.end(), bench.thrust.begin(), bench.thrust.end());
    clusters.insert(clusters.end(), bench.arms.begin(), bench.arms.end());
    const ResidualStatistics thrust = ComputeResidualStatistics(problem, bench.thrust, 1, 0);
    const ResidualStatistics arms = ComputeResidualStatistics(problem, bench.arms, 1, 0);
    residuals->push_back(
        {ResidualBlock::kLoadCellJointFit, thrust.count, thrust.rms_whitened,
         ThrustResidualRmsN(*bench_logs, fit->ratio[kFlightThrust] * fit->scales.thrust_coeff_n_s2_rad2),
         VarianceInflation(thrust)});
    residuals->push_back({ResidualBlock::kClampedArmJointFit, arms.count, arms.rms_whitened,
                          arms.rms_whitened * options.strain_noise_rad, VarianceInflation(arms)});
  }
  return SharedSigmas(problem, fit->Blocks(), inflation, clusters, options.num_threads);
}

void IdentifyFlightArms(const std::vector<SensorLog>& logs, const BirotorParams& base,
                        const IdentificationOptions& options, IdentificationResult* result,
                        const std::vector<SensorLog>* bench_logs) {
  // The motor time constant identified just before (IdentifyMotorTimeConstant), else the base value.
  ReportProgress(options, {"flight: samples and windows", 0, 0, 0.1});
  const FlightSamples data = CollectFlightSamples(logs, base, result->params, options);
  const std::vector<FlightWindow> windows = SelectFlightWindows(data.candidates, options.flight_max_windows);
  FlightProblem fit;
  BuildFlightProblem(data, windows, base, options, bench_logs, &fit);
  if (fit.windows.empty()) {
    result->errors.push_back("k, d, c_T: no STRAIN samples with MOTOR telemetry (omega_meas) at the same time");
    result->estimates.push_back(ParameterEstimate::Named("arm_stiffness_n_m_rad", "k"));
    result->estimates.push_back(ParameterEstimate::Named("arm_damping_n_m_s_rad", "d"));
    result->estimates.push_back(ParameterEstimate::Named("thrust_coeff_n_s2_rad2", "c_T"));
    return;
  }
  // Determinability of m_p (issue 26): the fit with m_p held first (the
  // default is never worse than holding it; from zero turbulence with m_p
  // free the solver can fall into a far minimum: hover 12 s, m_p +173 %),
  // then m_p freed only when the log's own excitation determines it.
  TipMassCheck tip_check = CheckTipMass(options, &fit);
  if (tip_check.applies && tip_check.free) ResolveFlightProblem(options, &fit, 0.7);
  ReportProgress(options, {"flight: sigmas", static_cast<int>(fit.windows.size()), 0, 0.9});
  std::vector<ResidualSummary> residuals;
  const std::vector<BlockSigma> sigma = FlightSigmas(options, data.any_imu, bench_logs, &fit, &residuals);
  if (tip_check.applies && tip_check.free) {
    // The base file's m_p (a bench's, 0.1 %) stands unless this flight shows
    // it wrong: m_p g enters every force the estimator gives, so a flight
    // m_p of 0.5 % sigma that agrees with it would only add its own error
    // (gentle 15 s: m_p +1.7 %, estimator MAE +16 %). k and c_T stay those
    // of the fit with m_p free (their sigmas carry m_p's uncertainty).
    const double sigma_ratio = sigma[kFlightTipMass].sigma;
    tip_check.flight_value_kg = fit.ratio[kFlightTipMass] * fit.scales.tip_mass_kg;
    tip_check.flight_sigma_kg = sigma_ratio * fit.scales.tip_mass_kg;
    tip_check.sigmas_from_base = sigma_ratio > 0.0 ? std::abs(fit.ratio[kFlightTipMass] - 1.0) / sigma_ratio : kNaN;
    if (!(tip_check.sigmas_from_base > options.consistency_sigmas)) {
      tip_check.agrees_with_base = true;
      tip_check.free = false;
    }
  }
  result->residuals.insert(result->residuals.end(), residuals.begin(), residuals.end());
  StoreFlightResult(fit, data, sigma, tip_check, base, options, result);
  const std::vector<FitPlot> plots = FlightPlots(fit);
  result->plots.insert(result->plots.end(), plots.begin(), plots.end());
}

}  // namespace birotor
