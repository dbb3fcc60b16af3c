// Ceres residual of the static thrust map on the bench: load-cell force
// against measured rotor speed, f = c_T omega^2.
#pragma once

#include <ceres/autodiff_cost_function.h>

namespace birotor {

// r = (f_meas - theta c_T,scale omega_meas^2) / sigma_f          [1, whitened]
// theta = c_T / c_T,scale is the parameter (order one for the solver);
// sigma_f^2 = sigma_loadcell^2 + (eta_std f)^2 + (2 c_T omega sigma_omega)^2
// covers load-cell noise, turbulence and telemetry noise.
struct ThrustResidual {
  ThrustResidual(double force_n, double omega_rad_s, double sigma_n, double thrust_coeff_scale)
      : force_n_(force_n),
        omega_sq_(omega_rad_s * omega_rad_s),
        inv_sigma_(1.0 / sigma_n),
        scale_(thrust_coeff_scale) {}

  template <typename T>
  bool operator()(const T* thrust_coeff_ratio, T* residual) const {
    residual[0] = (force_n_ - thrust_coeff_ratio[0] * (scale_ * omega_sq_)) * inv_sigma_;
    return true;
  }

  static ceres::CostFunction* Create(double force_n, double omega_rad_s, double sigma_n, double thrust_coeff_scale) {
    return new ceres::AutoDiffCostFunction<ThrustResidual, 1, 1>(
        new ThrustResidual(force_n, omega_rad_s, sigma_n, thrust_coeff_scale));
  }

  const double force_n_;
  const double omega_sq_;   // [rad^2/s^2]
  const double inv_sigma_;  // [1/N]
  const double scale_;      // [N s^2/rad^2]
};

}  // namespace birotor
