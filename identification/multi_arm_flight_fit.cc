// IdentifyMultiArmFlight (multi_arm_flight_fit.h): the count check, every
// rotor's tau_m from its telemetry, then the free-flight fit of every k_i and
// c_T,i in one problem (the arms share the body, so their windows do too).
#include "identification/multi_arm_flight_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "identification/fit_stages.h"
#include "identification/fit_support.h"
#include "identification/identify.h"
#include "identification/multi_arm_fit_parts.h"
#include "model/plant.h"

namespace birotor {
namespace {

constexpr int64_t kMaxMotorGapUs = 10000;  // motor model continued over at most 10 ms (the birotor's)
constexpr int64_t kMaxImuGapUs = 5000;
constexpr double kMotorSettleTimeConstants = 6.0;  // model speed trusted after 6 tau_m (0.25 % of the start error)
constexpr double kFinalTolerance = 1e-6;           // relative cost change that ends the solve (the birotor's)
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Rotor speeds of the first-order motor model of every rotor driven by the
// recorded commands (ZOH) at every MOTOR_N sample, as the birotor's flight
// fit: omega_{j+1} = MotorStep(omega_j, cmd_j, tau_m,i, dt), started from the
// telemetry (the command without it) after every gap, settled 6 tau_m later.
struct MultiArmModelSpeeds {
  std::vector<std::array<double, kMaxArms>> omega_rad_s;
  std::vector<bool> settled;
};

MultiArmModelSpeeds ModelRotorSpeeds(const std::vector<MultiArmMotorSample>& motor, const VehicleDescription& v) {
  const int n = v.arm_count;
  double slowest_s = 0.0;
  for (int i = 0; i < n; ++i) slowest_s = std::max(slowest_s, v.arms[static_cast<size_t>(i)].motor_time_constant_s);
  const int64_t settle_us = static_cast<int64_t>(kMotorSettleTimeConstants * slowest_s * 1e6);
  MultiArmModelSpeeds out;
  std::array<double, kMaxArms> unknown;
  unknown.fill(kNaN);
  out.omega_rad_s.assign(motor.size(), unknown);
  out.settled.assign(motor.size(), false);
  int64_t start_us = 0;
  for (size_t j = 0; j < motor.size(); ++j) {
    const MultiArmMotorSample& m = motor[j];
    bool commands_ok = true;
    for (int i = 0; i < n; ++i) commands_ok = commands_ok && std::isfinite(m.omega_cmd_rad_s[static_cast<size_t>(i)]);
    if (!commands_ok) continue;
    const bool continues = j > 0 && std::isfinite(out.omega_rad_s[j - 1][0]) &&
                           m.utime - motor[j - 1].utime <= kMaxMotorGapUs && m.utime > motor[j - 1].utime;
    if (!continues) start_us = m.utime;
    for (int i = 0; i < n; ++i) {
      const size_t r = static_cast<size_t>(i);
      out.omega_rad_s[j][r] =
          continues
              ? MotorStep(out.omega_rad_s[j - 1][r], ClampCommand(v.omega_max_rad_s, motor[j - 1].omega_cmd_rad_s[r]),
                          v.arms[r].motor_time_constant_s, 1e-6 * static_cast<double>(m.utime - motor[j - 1].utime))
          : std::isfinite(m.omega_meas_rad_s[r]) ? m.omega_meas_rad_s[r]
                                                 : ClampCommand(v.omega_max_rad_s, m.omega_cmd_rad_s[r]);
    }
    out.settled[j] = m.utime - start_us >= settle_us;
  }
  return out;
}

// The IMU at t into sample (NaN where it is missing).
void ImuAt(const std::vector<ImuSample>& imu, int64_t t_us, size_t* hint, MultiArmFlightWindowResidual::Sample* out) {
  size_t h0 = *hint, h1 = *hint, h2 = *hint;
  double g = kNaN, ax = kNaN, az = kNaN;
  const bool ok = InterpolateAt(
                      imu, t_us, kMaxImuGapUs, &h0, [](const ImuSample& m) { return m.gyro_y_rad_s; }, &g) &&
                  InterpolateAt(
                      imu, t_us, kMaxImuGapUs, &h1, [](const ImuSample& m) { return m.accel_x_m_s2; }, &ax) &&
                  InterpolateAt(
                      imu, t_us, kMaxImuGapUs, &h2, [](const ImuSample& m) { return m.accel_z_m_s2; }, &az);
  *hint = h0;
  out->gyro_rad_s = ok ? g : kNaN;
  out->accel_m_s2 = {ok ? ax : kNaN, ok ? az : kNaN};
}

// tau_m of rotor `rotor`: the birotor's motor fit on that rotor alone.
ParameterEstimate FitMotor(const std::vector<MultiArmBenchLog>& logs, const VehicleDescription& base, int rotor,
                           const IdentificationOptions& options, std::vector<std::string>* errors) {
  BirotorParams rotor_base;
  rotor_base.motor_time_constant_s = base.arms[static_cast<size_t>(rotor)].motor_time_constant_s;
  rotor_base.omega_max_rad_s = base.omega_max_rad_s;
  IdentificationResult result;
  IdentifyMotorTimeConstant(RotorAsBirotorLogs(logs, rotor), rotor_base, options, &result);
  const std::string n = std::to_string(rotor + 1);
  for (const std::string& e : result.errors) errors->push_back("rotor " + n + ": " + e);
  for (const ParameterEstimate& e : result.estimates) {
    if (e.key != "motor_time_constant_s") continue;
    ParameterEstimate out = e;
    out.symbol = "tau_m," + n;
    return out;
  }
  return ParameterEstimate::Named("motor_time_constant_s", "tau_m," + n);
}

// The held keys of arm `arm` with what to do about them.
void HeldKeys(int arm, ArmEstimates* e, std::vector<std::string>* advice) {
  const std::string n = std::to_string(arm + 1);
  e->damping = ParameterEstimate::Named("damping_n_m_s_rad", "d_" + n);
  e->damping.note.basis = EstimateBasis::kDampingNotFitted;
  e->gauge_offset = ParameterEstimate::Named("gauge_offset_rad", "o_" + n);
  advice->push_back("arm " + n +
                    ": d and the gauge offset NOT DETERMINED by a flight (held at the description's): the "
                    "free-flight windows barely see d, and o_i moves with k at a flight's nearly constant thrust; "
                    "identify d on the bench (birotor-identify --vehicle FILE --log BENCH) and tare the gauge at "
                    "power-up (an offset 2e-5 rad off moves k by about 1 %)");
}

// m_p of arm `arm` (ratio and its sigma): determined by the sigma rule, kept
// at the base value when within consistency_sigmas of it (the birotor's rule).
void TipMassEstimate(const MultiArmFlightProblem& fit, const BlockSigma& sigma, const VehicleDescription& base, int arm,
                     const IdentificationOptions& options, const EstimateNote& note, ArmEstimates* e,
                     std::vector<std::string>* advice) {
  const size_t a = static_cast<size_t>(arm);
  const std::string n = std::to_string(arm + 1);
  e->tip_mass = ParameterEstimate::Named("tip_mass_kg", "m_p," + n);
  if (!fit.fit_tip_mass) {
    advice->push_back("arm " + n + ": m_p NOT DETERMINED by a flight (held at the description's: " +
                      (options.flight_fit_tip_mass ? std::string("the N-arm flight fit does not model the rotor "
                                                                 "turbulence the description gives")
                                                   : std::string("flight_fit_tip_mass off")) +
                      "); k and c_T are only as good as this m_p: identify it on the bench first and fly against "
                      "the bench's description");
    return;
  }
  double ratio = fit.tip_mass_ratio[a];
  FillEstimate({&e->tip_mass, &ratio, base.arms[a].tip_mass_kg, 0.0}, sigma, options.max_relative_sigma, note);
  if (!e->tip_mass.determined) {
    advice->push_back("arm " + n +
                      ": m_p NOT DETERMINED by this flight (sigma above max_relative_sigma): fly "
                      "steps that ring this arm (its frequency sqrt(k / m_p)), or weigh the tip");
    return;
  }
  const double distance = std::abs(ratio - 1.0) / sigma.sigma;
  if (!(distance > options.consistency_sigmas)) {
    e->tip_mass.note.basis = EstimateBasis::kTipMassAgreesWithBase;
    e->tip_mass.note.value = e->tip_mass.value;
    e->tip_mass.note.sigma = e->tip_mass.sigma;
    e->tip_mass.note.distance_sigmas = distance;
    e->tip_mass.value = base.arms[a].tip_mass_kg;
  }
}

void Store(const ArmEstimates& e, ArmDescription* arm) {
  if (e.stiffness.determined) arm->stiffness_n_m_rad = e.stiffness.value;
  if (e.tip_mass.determined) arm->tip_mass_kg = e.tip_mass.value;
  if (e.thrust_coeff.determined) arm->thrust_coeff_n_s2_rad2 = e.thrust_coeff.value;
  if (e.motor_time_constant.determined) arm->motor_time_constant_s = e.motor_time_constant.value;
}

// Result stage of arm `arm`: k, c_T and m_p from the sigmas (empty: no
// window, nothing determined), d and o held, the errors and advice, the
// description's values.
void FillArm(const MultiArmFlightProblem& fit, const std::vector<BlockSigma>& sigma,
             const std::vector<double>& rms_whitened, const VehicleDescription& base, int arm,
             const IdentificationOptions& options, const EstimateNote& note, MultiArmIdentificationResult* result) {
  const int n = base.arm_count;
  const size_t a = static_cast<size_t>(arm);
  const std::string name = std::to_string(arm + 1);
  ArmEstimates& e = result->arms[a];
  e.stiffness = ParameterEstimate::Named("stiffness_n_m_rad", "k_" + name);
  e.thrust_coeff = ParameterEstimate::Named("thrust_coeff_n_s2_rad2", "c_T," + name);
  e.tip_mass = ParameterEstimate::Named("tip_mass_kg", "m_p," + name);
  e.strain_rms_whitened = rms_whitened[a];
  HeldKeys(arm, &e, &result->advice);
  if (!sigma.empty()) {
    double stiffness = fit.stiffness_ratio[a], thrust = fit.thrust_ratio[a];
    FillEstimate({&e.stiffness, &stiffness, base.arms[a].stiffness_n_m_rad, 0.0}, sigma[a], options.max_relative_sigma,
                 note);
    FillEstimate({&e.thrust_coeff, &thrust, base.arms[a].thrust_coeff_n_s2_rad2, 0.0},
                 sigma[static_cast<size_t>(n) + a], options.max_relative_sigma, note);
    TipMassEstimate(fit, sigma[2 * static_cast<size_t>(n) + a], base, arm, options, note, &e, &result->advice);
    if (!e.stiffness.determined) {
      result->errors.push_back("arm " + name + ": k not determined by the flight (fly steps that ring the arms)");
    }
    if (!e.thrust_coeff.determined) {
      result->errors.push_back("rotor " + name +
                               ": c_T not determined by the flight (fly manoeuvres that change this rotor's thrust)");
    }
  }
  Store(e, &result->vehicle.arms[a]);
}

}  // namespace

MultiArmFlightSamples CollectMultiArmFlightSamples(const std::vector<MultiArmBenchLog>& logs,
                                                   const VehicleDescription& motors,
                                                   const IdentificationOptions& options) {
  const int n = motors.arm_count;
  MultiArmFlightSamples data;
  data.utime.resize(logs.size());
  data.samples.resize(logs.size());
  for (size_t l = 0; l < logs.size(); ++l) {
    const MultiArmBenchLog& log = logs[l];
    const bool use_imu = options.use_imu && !log.imu.empty();
    data.any_imu = data.any_imu || use_imu;
    const MultiArmModelSpeeds speeds = ModelRotorSpeeds(log.motor, motors);
    std::vector<bool> valid(log.strain.size(), false);
    size_t motor_hint = 0, imu_hint = 0;
    for (const MultiArmStrainSample& s : log.strain) {
      MultiArmFlightWindowResidual::Sample out;
      bool ok = true;
      for (int i = 0; i < n; ++i) {
        const ArmDescription& arm = motors.arms[static_cast<size_t>(i)];
        out.deflection_rad[static_cast<size_t>(i)] =
            arm.has_gauge ? (s.deflection_rad[static_cast<size_t>(i)] - arm.gauge_offset_rad) / arm.gauge_scale : kNaN;
        ok = ok && (!arm.has_gauge || std::isfinite(out.deflection_rad[static_cast<size_t>(i)]));
      }
      // Exact ZOH motor response from the last MOTOR_N sample at or before t.
      while (motor_hint + 1 < log.motor.size() && log.motor[motor_hint + 1].utime <= s.utime) ++motor_hint;
      ok = ok && !log.motor.empty() && log.motor[motor_hint].utime <= s.utime &&
           s.utime - log.motor[motor_hint].utime <= kMaxMotorGapUs && speeds.settled[motor_hint];
      for (int i = 0; i < n && ok; ++i) {
        const size_t r = static_cast<size_t>(i);
        const MultiArmMotorSample& m = log.motor[motor_hint];
        out.omega_rad_s[r] =
            MotorStep(speeds.omega_rad_s[motor_hint][r], ClampCommand(motors.omega_max_rad_s, m.omega_cmd_rad_s[r]),
                      motors.arms[r].motor_time_constant_s, 1e-6 * static_cast<double>(s.utime - m.utime));
        ok = std::isfinite(out.omega_rad_s[r]);
      }
      out.gyro_rad_s = kNaN;
      out.accel_m_s2 = {kNaN, kNaN};
      if (use_imu) ImuAt(log.imu, s.utime, &imu_hint, &out);
      valid[data.samples[l].size()] = ok;
      data.utime[l].push_back(s.utime);
      data.samples[l].push_back(out);
    }
    const int64_t max_gap_us = 3 * std::max<int64_t>(MedianIntervalUs(data.utime[l]), 1);
    for (const auto& [begin, end] : ContiguousWindows(data.utime[l], valid, options.flight_window_s, max_gap_us, 20)) {
      data.candidates.push_back({l, begin, end});
    }
  }
  return data;
}

FlightState<double> InitialMultiArmWindowState(const std::vector<MultiArmFlightWindowResidual::Sample>& samples,
                                               int arm_count) {
  FlightState<double> x0 = FlightState<double>::Zero(FlightStateSize(arm_count));
  const MultiArmFlightWindowResidual::Sample& first = samples.front();
  x0(0) = std::isfinite(first.gyro_rad_s) ? first.gyro_rad_s : 0.0;
  const size_t fit_n = std::min<size_t>(samples.size(), 5);
  for (int arm = 0; arm < arm_count; ++arm) {
    const size_t a = static_cast<size_t>(arm);
    x0(FlightDeflectionIndex(arm)) = std::isfinite(first.deflection_rad[a]) ? first.deflection_rad[a] : 0.0;
    double st = 0.0, sb = 0.0, stt = 0.0, stb = 0.0, t = 0.0;
    for (size_t i = 0; i < fit_n; ++i) {
      const double b = std::isfinite(samples[i].deflection_rad[a]) ? samples[i].deflection_rad[a] : 0.0;
      st += t;
      sb += b;
      stt += t * t;
      stb += t * b;
      t += samples[i].dt_s;
    }
    const double det = static_cast<double>(fit_n) * stt - st * st;
    if (det > 0.0) x0(FlightRateIndex(arm_count, arm)) = (static_cast<double>(fit_n) * stb - st * sb) / det;
  }
  return x0;
}

void BuildMultiArmFlightProblem(const MultiArmFlightSamples& data, const std::vector<FlightWindow>& windows,
                                const VehicleDescription& base, const IdentificationOptions& options,
                                MultiArmFlightProblem* fit) {
  fit->arm_count = base.arm_count;
  const MultiArmFlightWindowResidual::Noise noise{options.strain_noise_rad, options.gyro_noise_rad_s,
                                                  options.accel_noise_m_s2, options.huber_threshold};
  for (const FlightWindow& w : windows) {
    const std::vector<int64_t>& utime = data.utime[w.log];
    std::vector<MultiArmFlightWindowResidual::Sample> samples(data.samples[w.log].begin() + w.begin,
                                                              data.samples[w.log].begin() + w.end);
    for (size_t i = 0; i + 1 < samples.size(); ++i) {
      samples[i].dt_s = 1e-6 * static_cast<double>(utime[w.begin + i + 1] - utime[w.begin + i]);
    }
    samples.back().dt_s = 0.0;
    const FlightState<double> x0 = InitialMultiArmWindowState(samples, base.arm_count);
    std::vector<double>& state = fit->states.emplace_back(x0.data(), x0.data() + x0.size());
    std::vector<double*> parameters = fit->Blocks();
    parameters.push_back(state.data());
    fit->windows.push_back(fit->problem.AddResidualBlock(
        MultiArmFlightWindowResidual::Create(base, std::move(samples), noise, options.flight_integration_substeps,
                                             options.flight_fit_tip_mass),
        nullptr, parameters));
  }
  if (fit->windows.empty()) return;
  for (double* block : fit->Blocks()) fit->problem.SetParameterLowerBound(block, 0, 1e-3);
  // The birotor's rule (flight_fit.h CheckTipMass): m_p is judged from a
  // flight only with the rotor turbulence modelled, which this fit does not
  // do; so only a vehicle without turbulence fits it. Unmodelled, 1 %
  // turbulence drove flight_id's m_p to twice the truth (0.58 kg for 0.27 kg)
  // and c_T 25-40 % high along the near-degenerate direction m_p, c_T, k up.
  fit->fit_tip_mass = options.flight_fit_tip_mass && base.turbulence_std == 0.0;
  for (int i = 0; i < base.arm_count && !fit->fit_tip_mass; ++i) {
    fit->problem.SetParameterBlockConstant(&fit->tip_mass_ratio[static_cast<size_t>(i)]);
  }
}

void SolveMultiArmFlightProblem(const IdentificationOptions& options, MultiArmFlightProblem* fit) {
  std::vector<double*> tip_masses;
  for (int i = 0; i < fit->arm_count; ++i) tip_masses.push_back(&fit->tip_mass_ratio[static_cast<size_t>(i)]);
  for (double* block : tip_masses) fit->problem.SetParameterBlockConstant(block);
  SolveProblem(options, &fit->problem, kFinalTolerance);
  if (!fit->fit_tip_mass) return;
  for (double* block : tip_masses) fit->problem.SetParameterBlockVariable(block);
  SolveProblem(options, &fit->problem, kFinalTolerance);
}

std::vector<BlockSigma> MultiArmFlightSigmas(const IdentificationOptions& options, bool any_imu,
                                             MultiArmFlightProblem* fit, std::vector<double>* strain_rms_whitened) {
  const int n = fit->arm_count;
  const int per_sample = FlightResidualsPerSample(n);
  double inflation = 1.0;
  strain_rms_whitened->assign(static_cast<size_t>(n), kNaN);
  for (int channel = 0; channel < per_sample; ++channel) {
    if (channel >= FlightGyroResidual(n) && !any_imu) continue;
    const ResidualStatistics stats = ComputeResidualStatistics(&fit->problem, fit->windows, per_sample, channel);
    if (stats.count == 0) continue;
    inflation = std::max(inflation, VarianceInflation(stats));
    if (channel < n) (*strain_rms_whitened)[static_cast<size_t>(channel)] = stats.rms_whitened;
  }
  return SharedSigmas(&fit->problem, fit->Blocks(), inflation, fit->windows, options.num_threads);
}

MultiArmIdentificationResult IdentifyMultiArmFlight(const std::vector<MultiArmBenchLog>& logs,
                                                    const VehicleDescription& base,
                                                    const IdentificationOptions& options) {
  MultiArmIdentificationResult result;
  result.flight = true;
  result.vehicle = base;
  for (const MultiArmBenchLog& log : logs) {
    const std::string why = MultiArmLogMismatch(log, base);
    if (!why.empty()) result.errors.push_back(why);
  }
  if (logs.empty()) result.errors.push_back("no log");
  if (options.calibration.TipMassWeighed() || options.calibration.gauge_scale_std > 0.0) {
    result.errors.push_back("a calibration fact (weighed tip mass, gauge scale sigma) is not supported for N arms");
  }
  if (!result.errors.empty()) return result;
  const int n = base.arm_count;
  result.arms.resize(static_cast<size_t>(n));
  // tau_m first: the motor model of the free-flight windows runs on it.
  VehicleDescription motors = base;
  for (int i = 0; i < n; ++i) {
    ArmEstimates& e = result.arms[static_cast<size_t>(i)];
    e.motor_time_constant = FitMotor(logs, base, i, options, &result.errors);
    if (e.motor_time_constant.determined) {
      motors.arms[static_cast<size_t>(i)].motor_time_constant_s = e.motor_time_constant.value;
    }
  }
  const MultiArmFlightSamples data = CollectMultiArmFlightSamples(logs, motors, options);
  const std::vector<FlightWindow> windows = SelectFlightWindows(data.candidates, options.flight_max_windows);
  MultiArmFlightProblem fit;
  BuildMultiArmFlightProblem(data, windows, base, options, &fit);
  EstimateNote note;
  note.basis = EstimateBasis::kFreeArmFit;
  note.windows = static_cast<int>(fit.windows.size());
  note.candidate_windows = static_cast<int>(data.candidates.size());
  note.with_imu = data.any_imu;
  std::vector<BlockSigma> sigma;
  std::vector<double> rms_whitened(static_cast<size_t>(n), kNaN);
  if (!fit.windows.empty()) {
    SolveMultiArmFlightProblem(options, &fit);
    sigma = MultiArmFlightSigmas(options, data.any_imu, &fit, &rms_whitened);
  } else {
    result.errors.push_back("k, c_T: no STRAIN_N samples with MOTOR_N commands (settled motor model) at the same time");
  }
  for (int i = 0; i < n; ++i) {
    FillArm(fit, sigma, rms_whitened, base, i, options, note, &result);
  }
  result.ok = result.errors.empty();
  return result;
}

}  // namespace birotor
