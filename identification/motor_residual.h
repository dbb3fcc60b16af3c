// Ceres residual of the motor time constant: output error of the first-order
// rotor speed model over one window of recorded commands and telemetry.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <cmath>
#include <vector>

#include "identification/robust_residual.h"
#include "model/plant.h"

namespace birotor {

// One window of MOTOR samples j = 0..N-1. The speed is simulated from the
// window's own initial speed omega_0 (a parameter) with the command of sample
// j held until sample j+1 (the commands are zero-order held, as the
// controller applies them):
//   omega_{j+1} = c_j + (omega_j - c_j) exp(-dt_j / tau_m),   tau_m = theta tau_scale
//   r_j = Huber((omega_meas_j - omega_j) / sigma_omega)           [1, whitened]
// A sample without telemetry (NaN) gives r_j = 0.
struct MotorWindowResidual {
  struct Sample {
    double dt_s;              // time to the next sample [s] (unused for the last)
    double omega_cmd_rad_s;   // clamped command, held until the next sample
    double omega_meas_rad_s;  // telemetry, NaN when absent
  };

  MotorWindowResidual(std::vector<Sample> samples, double sigma_rad_s, double tau_scale_s, double huber)
      : samples_(std::move(samples)), inv_sigma_(1.0 / sigma_rad_s), tau_scale_s_(tau_scale_s), huber_(huber) {}

  template <typename T>
  bool operator()(const T* tau_ratio, const T* omega0_rad_s, T* residual) const {
    const T tau_s = tau_ratio[0] * tau_scale_s_;
    T omega = omega0_rad_s[0];
    for (size_t j = 0; j < samples_.size(); ++j) {
      if (j > 0) omega = MotorStep(omega, samples_[j - 1].omega_cmd_rad_s, tau_s, samples_[j - 1].dt_s);
      const double meas = samples_[j].omega_meas_rad_s;
      residual[j] = std::isfinite(meas) ? HuberResidual(T((meas - omega) * inv_sigma_), huber_) : T(0.0);
    }
    return true;
  }

  static ceres::CostFunction* Create(std::vector<Sample> samples, double sigma_rad_s, double tau_scale_s,
                                     double huber) {
    const int n = static_cast<int>(samples.size());
    return new ceres::AutoDiffCostFunction<MotorWindowResidual, ceres::DYNAMIC, 1, 1>(
        new MotorWindowResidual(std::move(samples), sigma_rad_s, tau_scale_s, huber), n);
  }

  const std::vector<Sample> samples_;
  const double inv_sigma_;    // [s/rad]
  const double tau_scale_s_;  // [s]
  const double huber_;        // Huber threshold [sigma]
};

}  // namespace birotor
