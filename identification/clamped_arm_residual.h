// Ceres residual of the arm stiffness and damping on the bench: output error
// of the clamped arm driven by the measured load-cell force, over one window.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <vector>

#include "identification/arm_dynamics.h"
#include "identification/robust_residual.h"

namespace birotor {

// One window of paired STRAIN/LOADCELL samples j = 0..N-1 of arm i. The
// deflection is integrated (RK4, `substeps` per interval, force linear between
// samples) from the window's own initial state (b_0, b_dot_0) through
//   m_p L^2 b_ddot + d b_dot + k b + s_i m_p g L cos(b) = s_i L f_i
// with k = theta_k k_scale, d = theta_d d_scale, and
//   r_j = Huber((b_meas_j - b_j) / sigma_b)                         [1, whitened]
struct ClampedArmWindowResidual {
  struct Sample {
    double dt_s;            // time to the next sample [s] (unused for the last)
    double force_n;         // load-cell force at this sample [N]
    double deflection_rad;  // strain-gauge deflection at this sample [rad]
  };

  ClampedArmWindowResidual(const VehicleParams& known, int arm, std::vector<Sample> samples, double sigma_rad,
                           int substeps, double k_scale, double d_scale, double huber)
      : known_(known),
        arm_(arm),
        samples_(std::move(samples)),
        inv_sigma_(1.0 / sigma_rad),
        substeps_(substeps),
        k_scale_(k_scale),
        d_scale_(d_scale),
        huber_(huber) {}

  template <typename T>
  bool operator()(const T* k_ratio, const T* d_ratio, const T* state0, T* residual) const {
    const T k = k_ratio[0] * k_scale_;
    const T d = d_ratio[0] * d_scale_;
    T b = state0[0], b_dot = state0[1];
    for (size_t j = 0; j < samples_.size(); ++j) {
      if (j > 0) {
        const Sample& s0 = samples_[j - 1];
        const double f0 = s0.force_n, df = samples_[j].force_n - s0.force_n;
        const double h = s0.dt_s / substeps_;
        for (int s = 0; s < substeps_; ++s) {
          const double a0 = static_cast<double>(s) / substeps_;
          const double a1 = static_cast<double>(s + 1) / substeps_;
          const T fa(f0 + df * a0), fm(f0 + df * 0.5 * (a0 + a1)), fb(f0 + df * a1);
          const T k1b = b_dot, k1v = ClampedArmAcceleration(known_, arm_, k, d, b, b_dot, fa);
          const T b2 = b + 0.5 * h * k1b, v2 = b_dot + 0.5 * h * k1v;
          const T k2b = v2, k2v = ClampedArmAcceleration(known_, arm_, k, d, b2, v2, fm);
          const T b3 = b + 0.5 * h * k2b, v3 = b_dot + 0.5 * h * k2v;
          const T k3b = v3, k3v = ClampedArmAcceleration(known_, arm_, k, d, b3, v3, fm);
          const T b4 = b + h * k3b, v4 = b_dot + h * k3v;
          const T k4b = v4, k4v = ClampedArmAcceleration(known_, arm_, k, d, b4, v4, fb);
          b = b + (h / 6.0) * (k1b + 2.0 * k2b + 2.0 * k3b + k4b);
          b_dot = b_dot + (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        }
      }
      residual[j] = HuberResidual(T((samples_[j].deflection_rad - b) * inv_sigma_), huber_);
    }
    return true;
  }

  static ceres::CostFunction* Create(const VehicleParams& known, int arm, std::vector<Sample> samples, double sigma_rad,
                                     int substeps, double k_scale, double d_scale, double huber) {
    const int n = static_cast<int>(samples.size());
    return new ceres::AutoDiffCostFunction<ClampedArmWindowResidual, ceres::DYNAMIC, 1, 1, 2>(
        new ClampedArmWindowResidual(known, arm, std::move(samples), sigma_rad, substeps, k_scale, d_scale, huber), n);
  }

  const VehicleParams known_;  // m_p, L, g (k and d are parameters)
  const int arm_;              // 0: arm 1, 1: arm 2
  const std::vector<Sample> samples_;
  const double inv_sigma_;  // [1/rad]
  const int substeps_;
  const double k_scale_;  // [N m/rad]
  const double d_scale_;  // [N m s/rad]
  const double huber_;    // Huber threshold [sigma]
};

}  // namespace birotor
