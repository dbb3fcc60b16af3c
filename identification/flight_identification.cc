// Flight identification (no load cells): k, d and c_T from the free-flight
// arm dynamics driven by the rotor speed telemetry, predicting deflections
// and, when the IMU is present, pitch rate and specific force.
#include <ceres/ceres.h>

#include <array>
#include <cmath>
#include <deque>

#include "identification/fit_support.h"
#include "identification/free_arm_residual.h"
#include "identification/identify.h"

namespace birotor {
namespace {

constexpr int64_t kMaxMotorGapUs = 10000;  // interpolate telemetry over at most 10 ms
constexpr int64_t kMaxImuGapUs = 5000;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

void IdentifyFlightArms(const std::vector<SensorLog>& logs, const VehicleParams& base,
                        const IdentificationOptions& options, IdentificationResult* result) {
  FreeArmWindowResidual::Scales scales;
  scales.stiffness_n_m_rad = base.arm_stiffness_n_m_rad;
  scales.damping_n_m_s_rad = base.arm_damping_n_m_s_rad > 0.0 ? base.arm_damping_n_m_s_rad : 0.1;
  scales.thrust_coeff_n_s2_rad2 = base.thrust_coeff_n_s2_rad2;
  FreeArmWindowResidual::Noise noise{options.strain_noise_rad, options.gyro_noise_rad_s, options.accel_noise_m_s2,
                                     options.huber_threshold};

  ceres::Problem problem;
  double k_ratio = 1.0;
  double d_ratio = base.arm_damping_n_m_s_rad / scales.damping_n_m_s_rad;
  double c_ratio = 1.0;
  std::deque<std::array<double, kFreeArmStateSize>> states;
  std::vector<ceres::ResidualBlockId> blocks;
  bool any_imu = false;
  for (const SensorLog& log : logs) {
    const bool use_imu = options.use_imu && !log.imu.empty();
    any_imu = any_imu || use_imu;
    const size_t n = log.strain.size();
    std::vector<int64_t> utime(n);
    std::vector<bool> valid(n);
    std::vector<FreeArmWindowResidual::Sample> all(n);
    size_t motor_hint = 0, imu_hint = 0;
    for (size_t i = 0; i < n; ++i) {
      const StrainSample& s = log.strain[i];
      utime[i] = s.utime;
      FreeArmWindowResidual::Sample& out = all[i];
      out.deflection_rad[0] = s.deflection_rad[0];
      out.deflection_rad[1] = s.deflection_rad[1];
      bool ok = std::isfinite(s.deflection_rad[0]) && std::isfinite(s.deflection_rad[1]);
      for (int rotor = 0; rotor < 2 && ok; ++rotor) {
        size_t hint = motor_hint;
        ok = InterpolateAt(log.motor, s.utime, kMaxMotorGapUs, &hint,
                           [rotor](const MotorSample& m) { return m.omega_meas_rad_s[rotor]; },
                           &out.omega_rad_s[rotor]) &&
             std::isfinite(out.omega_rad_s[rotor]);
        if (rotor == 1) motor_hint = hint;
      }
      out.gyro_rad_s = out.accel_m_s2[0] = out.accel_m_s2[1] = kNaN;
      if (use_imu) {
        size_t h0 = imu_hint, h1 = imu_hint, h2 = imu_hint;
        double g = kNaN, ax = kNaN, az = kNaN;
        if (InterpolateAt(log.imu, s.utime, kMaxImuGapUs, &h0, [](const ImuSample& m) { return m.gyro_y_rad_s; }, &g) &&
            InterpolateAt(log.imu, s.utime, kMaxImuGapUs, &h1, [](const ImuSample& m) { return m.accel_x_m_s2; }, &ax) &&
            InterpolateAt(log.imu, s.utime, kMaxImuGapUs, &h2, [](const ImuSample& m) { return m.accel_z_m_s2; }, &az)) {
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
      std::vector<FreeArmWindowResidual::Sample> samples(all.begin() + begin, all.begin() + end);
      for (size_t i = 0; i + 1 < samples.size(); ++i) {
        samples[i].dt_s = 1e-6 * static_cast<double>(utime[begin + i + 1] - utime[begin + i]);
      }
      samples.back().dt_s = 0.0;
      const FreeArmWindowResidual::Sample& first = samples.front();
      states.push_back({std::isfinite(first.gyro_rad_s) ? first.gyro_rad_s : 0.0, first.deflection_rad[0],
                        first.deflection_rad[1], 0.0, 0.0});
      blocks.push_back(problem.AddResidualBlock(
          FreeArmWindowResidual::Create(base, std::move(samples), noise, options.integration_substeps, scales),
          nullptr, &k_ratio, &d_ratio, &c_ratio, states.back().data()));
    }
  }
  ParameterEstimate k, damping, c_t;
  k.key = "arm_stiffness_n_m_rad";
  k.symbol = "k";
  damping.key = "arm_damping_n_m_s_rad";
  damping.symbol = "d";
  c_t.key = "thrust_coeff_n_s2_rad2";
  c_t.symbol = "c_T";
  if (blocks.empty()) {
    result->errors.push_back("k, d, c_T: no STRAIN samples with MOTOR telemetry (omega_meas) at the same time");
    result->estimates.insert(result->estimates.end(), {k, damping, c_t});
    return;
  }
  problem.SetParameterLowerBound(&k_ratio, 0, 1e-3);
  problem.SetParameterLowerBound(&c_ratio, 0, 1e-3);
  problem.SetParameterLowerBound(&d_ratio, 0, 0.0);
  SolveProblem(options, &problem);

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
    const ResidualStatistics stats =
        ComputeResidualStatistics(&problem, blocks, kFreeArmResidualsPerSample, channel);
    if (stats.count == 0) continue;
    const double channel_inflation = VarianceInflation(stats);
    inflation = std::max(inflation, channel_inflation);
    result->residuals.push_back({names[channel], units[channel], stats.count, stats.rms_whitened,
                                 stats.rms_whitened * sigmas[channel], channel_inflation});
  }
  const std::vector<BlockSigma> sigma =
      ComputeBlockSigmas(&problem, {&k_ratio, &d_ratio, &c_ratio}, inflation, options.num_threads);
  const std::string note = "output error of the free-flight arm model over " + std::to_string(blocks.size()) +
                           " windows" + (any_imu ? " with IMU" : " without IMU");
  auto fill = [&](ParameterEstimate* e, double ratio, double scale, const BlockSigma& s) {
    e->value = ratio * scale;
    e->sigma = s.sigma * scale;
    e->determined = s.determined && e->sigma <= options.max_relative_sigma * std::abs(e->value);
    e->note = note;
  };
  fill(&k, k_ratio, scales.stiffness_n_m_rad, sigma[0]);
  fill(&damping, d_ratio, scales.damping_n_m_s_rad, sigma[1]);
  fill(&c_t, c_ratio, scales.thrust_coeff_n_s2_rad2, sigma[2]);
  if (!k.determined) result->errors.push_back("k: not determined by the flight data (arm dynamics not excited)");
  if (!c_t.determined) {
    result->errors.push_back(std::string("c_T: not determined by the flight data") +
                             (any_imu ? "" : " (no IMU: only c_T / k is seen by the strain gauges)"));
  }
  if (!damping.determined) result->warnings.push_back("d: not determined by the flight data; base value kept");
  result->estimates.insert(result->estimates.end(), {k, damping, c_t});
  if (k.determined) result->params.arm_stiffness_n_m_rad = k.value;
  if (damping.determined) result->params.arm_damping_n_m_s_rad = damping.value;
  if (c_t.determined) result->params.thrust_coeff_n_s2_rad2 = c_t.value;
}

}  // namespace birotor
