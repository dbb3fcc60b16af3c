// tau_m from MOTOR telemetry against commands (bench and flight).
#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <sstream>
#include <string>

#include "identification/fit_support.h"
#include "identification/identify.h"
#include "identification/motor_residual.h"
#include "model/plant.h"
#include "samples/rotor_count.h"

namespace birotor {

std::string MotorNotExcitedError(const EstimateNote& note) {
  std::ostringstream text;
  text << "tau_m cannot be identified: no excitation (the commands have " << note.command_steps[0] << " and "
       << note.command_steps[1] << " steps larger than " << note.step_threshold_rad_s
       << " rad/s; record motor command steps or a chirp)";
  return text.str();
}

void IdentifyMotorTimeConstant(const std::vector<SensorLog>& logs, const BirotorParams& base,
                               const IdentificationOptions& options, IdentificationResult* result) {
  ceres::Problem::Options problem_options;
  ceres::Problem problem(problem_options);
  double tau_ratio = 1.0;
  std::deque<double> omega0;
  std::vector<ceres::ResidualBlockId> blocks;
  int steps[kBirotorRotors] = {0, 0};
  // For the plot: the window with the largest command step.
  std::vector<MotorWindowResidual::Sample> plot_samples;
  size_t plot_block = 0;
  double plot_step_rad_s = 0.0;
  for (const SensorLog& log : logs) {
    std::vector<int64_t> utime;
    utime.reserve(log.motor.size());
    for (const MotorSample& m : log.motor) utime.push_back(m.utime);
    const int64_t max_gap_us = 3 * std::max<int64_t>(MedianIntervalUs(utime), 1);
    for (int rotor = 0; rotor < kBirotorRotors; ++rotor) {
      std::vector<bool> valid(log.motor.size());
      for (size_t i = 0; i < log.motor.size(); ++i) {
        valid[i] =
            std::isfinite(log.motor[i].omega_meas_rad_s[rotor]) && std::isfinite(log.motor[i].omega_cmd_rad_s[rotor]);
        if (i > 0 && std::abs(log.motor[i].omega_cmd_rad_s[rotor] - log.motor[i - 1].omega_cmd_rad_s[rotor]) >
                         options.command_step_rad_s) {
          ++steps[rotor];
        }
      }
      for (const auto& [begin, end] : ContiguousWindows(utime, valid, options.motor_window_s, max_gap_us, 10)) {
        std::vector<MotorWindowResidual::Sample> samples;
        samples.reserve(end - begin);
        for (size_t i = begin; i < end; ++i) {
          const MotorSample& m = log.motor[i];
          const double dt_s = (i + 1 < end) ? 1e-6 * static_cast<double>(log.motor[i + 1].utime - m.utime) : 0.0;
          samples.push_back({dt_s, ClampCommand(base, m.omega_cmd_rad_s[rotor]), m.omega_meas_rad_s[rotor]});
        }
        omega0.push_back(samples.front().omega_meas_rad_s);
        for (size_t i = 1; i < samples.size(); ++i) {
          const double step = std::abs(samples[i].omega_cmd_rad_s - samples[i - 1].omega_cmd_rad_s);
          if (step > plot_step_rad_s) {
            plot_step_rad_s = step;
            plot_samples = samples;
            plot_block = blocks.size();
          }
        }
        blocks.push_back(
            problem.AddResidualBlock(MotorWindowResidual::Create(std::move(samples), options.telemetry_noise_rad_s,
                                                                 base.motor_time_constant_s, options.huber_threshold),
                                     nullptr, &tau_ratio, &omega0.back()));
      }
    }
  }
  ParameterEstimate tau;
  tau.key = "motor_time_constant_s";
  tau.symbol = "tau_m";
  if (blocks.empty()) {
    result->errors.push_back("tau_m: no MOTOR samples with both a command and telemetry (omega_meas) in any log");
    result->estimates.push_back(tau);
    return;
  }
  problem.SetParameterLowerBound(&tau_ratio, 0, 1e-3);
  problem.SetParameterUpperBound(&tau_ratio, 0, 1e3);
  const FitProgress at{"motor: tau_m", static_cast<int>(blocks.size()), 0, 0.0};
  SolveProblem(options, &problem, 1e-10, &at);

  const ResidualStatistics stats = ComputeResidualStatistics(&problem, blocks, 1, 0);
  const double inflation = VarianceInflation(stats);
  const std::vector<BlockSigma> sigma = ComputeBlockSigmas(&problem, {&tau_ratio}, inflation, options.num_threads);
  tau.value = tau_ratio * base.motor_time_constant_s;
  tau.sigma = sigma[0].sigma * base.motor_time_constant_s;
  // Excitation: min_command_steps steps on a motor, or a continuous variation
  // of the commands that the fit's sigma shows (for a first-order motor the
  // relative sigma is about sigma_n / sqrt(sum (tau dw_cmd/dt)^2), sigma_n the
  // telemetry noise): determined only when that sigma says so.
  tau.determined = SigmaDetermines(sigma[0].determined, tau.value, tau.sigma, options.max_relative_sigma);
  const bool stepped = std::max(steps[0], steps[1]) >= options.min_command_steps;
  tau.note.basis = !tau.determined ? EstimateBasis::kMotorNotExcited
                   : stepped       ? EstimateBasis::kMotorFit
                                   : EstimateBasis::kMotorFitContinuous;
  tau.note.relative_sigma = tau.sigma / std::abs(tau.value);
  tau.note.windows = static_cast<int>(blocks.size());
  tau.note.command_steps[0] = steps[0];
  tau.note.command_steps[1] = steps[1];
  tau.note.step_threshold_rad_s = options.command_step_rad_s;
  if (!tau.determined) result->errors.push_back(MotorNotExcitedError(tau.note));
  result->estimates.push_back(tau);
  result->residuals.push_back({ResidualBlock::kMotorTelemetry, stats.count, stats.rms_whitened,
                               stats.rms_whitened * options.telemetry_noise_rad_s, inflation});
  if (tau.determined) result->params.motor_time_constant_s = tau.value;
  if (!plot_samples.empty()) {
    // Fitted ZOH first-order response from the window's fitted initial speed.
    FitPlot plot;
    plot.panel = FitPanel::kMotorResponse;
    plot.value = tau.value;
    double omega = omega0[plot_block], t_s = 0.0;
    for (size_t j = 0; j < plot_samples.size(); ++j) {
      if (j > 0) {
        omega = MotorStep(omega, plot_samples[j - 1].omega_cmd_rad_s, tau.value, plot_samples[j - 1].dt_s);
        t_s += plot_samples[j - 1].dt_s;
      }
      plot.x.push_back(t_s);
      plot.data.push_back(plot_samples[j].omega_meas_rad_s);
      plot.model.push_back(omega);
    }
    result->plots.push_back(std::move(plot));
  }
}

}  // namespace birotor
