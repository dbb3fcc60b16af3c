// Ceres residual of the arm stiffness, damping, tip mass and gauge
// calibration on the bench: output error of the clamped arm driven by the
// measured load-cell force, read through the gauge, over one window.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>
#include <vector>

#include "identification/robust_residual.h"
#include "model/arm_dynamics.h"
#include "model/rk4.h"

namespace birotor {

// One window of paired STRAIN/LOADCELL samples j = 0..N-1 of arm i. The
// deflection is integrated (RK4, `substeps` per interval, force linear between
// samples) from the window's own initial state (b_0, b_dot_0) through
//   m_p L^2 b_ddot + d b_dot + k b + m_p g L cos(b + alpha) = l f_i
// (model/arm_dynamics.h ClampedArmGeometry; the birotor's arm i has
// alpha = pi or 0 and l = s_i L, s_i the arm sign) with k = theta_k k_scale,
// d = theta_d d_scale, m_p = theta_m m_scale, and read through the gauge
// (shared/spec/gauges.md) with scale g_i and offset o_i = theta_o sigma_b:
//   r_j = Huber((b_meas_j - (g_i b_j + o_i)) / sigma_b)              [1, whitened]
struct ClampedArmWindowResidual {
  struct Sample {
    double dt_s;            // time to the next sample [s] (unused for the last)
    double force_n;         // load-cell force at this sample [N]
    double deflection_rad;  // strain-gauge reading at this sample [rad]
  };
  // Units of the parameter ratios (order one for the solver).
  struct Scales {
    double stiffness_n_m_rad;
    double damping_n_m_s_rad;
    double tip_mass_kg;
  };

  ClampedArmWindowResidual(const BirotorParams& known, int arm, std::vector<Sample> samples, double sigma_rad,
                           int substeps, const Scales& scales, double huber)
      : ClampedArmWindowResidual(BirotorClampedArm(known, arm), arm, std::move(samples), sigma_rad, substeps, scales,
                                 huber) {}
  // Any vehicle's arm; slot: the index of this arm's gauge blocks in the
  // fit's parameter layout (bench_fit.h BenchTheta: 0 or 1).
  ClampedArmWindowResidual(const ClampedArmGeometry& geometry, int slot, std::vector<Sample> samples, double sigma_rad,
                           int substeps, const Scales& scales, double huber)
      : geometry_(geometry),
        arm_(slot),
        samples_(std::move(samples)),
        sigma_rad_(sigma_rad),
        substeps_(substeps),
        scales_(scales),
        huber_(huber) {}

  // gauge_scale: g_i [1]; offset_ratio: o_i / sigma_b [1]; state0: (b_0 [rad], b_dot_0 [rad/s]).
  template <typename T>
  bool operator()(const T* k_ratio, const T* d_ratio, const T* tip_mass_ratio, const T* gauge_scale,
                  const T* offset_ratio, const T* state0, T* residual) const {
    const T k = k_ratio[0] * scales_.stiffness_n_m_rad;
    const T d = d_ratio[0] * scales_.damping_n_m_s_rad;
    const T mp = tip_mass_ratio[0] * scales_.tip_mass_kg;
    const T offset_rad = offset_ratio[0] * sigma_rad_;
    using State = Eigen::Matrix<T, 2, 1>;  // (b [rad], b_dot [rad/s])
    State x(state0[0], state0[1]);
    const double inv_sigma = 1.0 / sigma_rad_;
    for (size_t j = 0; j < samples_.size(); ++j) {
      if (j > 0) {
        const Sample& s0 = samples_[j - 1];
        const double f0 = s0.force_n, df = samples_[j].force_n - s0.force_n;
        const double h = s0.dt_s / substeps_;
        for (int s = 0; s < substeps_; ++s) {
          const double a0 = static_cast<double>(s) / substeps_;
          const double a1 = static_cast<double>(s + 1) / substeps_;
          // Force at the start, middle and end of the substep (Rk4Stage order).
          const T force[3] = {T(f0 + df * a0), T(f0 + df * 0.5 * (a0 + a1)), T(f0 + df * a1)};
          x = Rk4Step(x, h, [&](const State& y, Rk4Stage stage) {
            return State(y(1),
                         ClampedArmAcceleration<T>(geometry_, k, d, mp, y(0), y(1), force[static_cast<int>(stage)]));
          });
        }
      }
      residual[j] =
          HuberResidual(T((samples_[j].deflection_rad - (gauge_scale[0] * x(0) + offset_rad)) * inv_sigma), huber_);
    }
    return true;
  }

  static ceres::CostFunction* Create(const BirotorParams& known, int arm, std::vector<Sample> samples, double sigma_rad,
                                     int substeps, const Scales& scales, double huber) {
    const int n = static_cast<int>(samples.size());
    return new ceres::AutoDiffCostFunction<ClampedArmWindowResidual, ceres::DYNAMIC, 1, 1, 1, 1, 1, 2>(
        new ClampedArmWindowResidual(known, arm, std::move(samples), sigma_rad, substeps, scales, huber), n);
  }
  static ceres::CostFunction* Create(const ClampedArmGeometry& geometry, int slot, std::vector<Sample> samples,
                                     double sigma_rad, int substeps, const Scales& scales, double huber) {
    const int n = static_cast<int>(samples.size());
    return new ceres::AutoDiffCostFunction<ClampedArmWindowResidual, ceres::DYNAMIC, 1, 1, 1, 1, 1, 2>(
        new ClampedArmWindowResidual(geometry, slot, std::move(samples), sigma_rad, substeps, scales, huber), n);
  }

  const ClampedArmGeometry geometry_;  // L, l, alpha, g (k, d, m_p are parameters)
  const int arm_;                      // gauge slot: 0 (birotor arm 1), 1 (arm 2)
  const std::vector<Sample> samples_;
  const double sigma_rad_;  // strain noise, also the unit of the offset ratio [rad]
  const int substeps_;
  const Scales scales_;
  const double huber_;  // Huber threshold [sigma]
};

}  // namespace birotor
