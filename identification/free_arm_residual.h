// Ceres residual of stiffness, damping and thrust coefficient in free flight:
// output error of the arm and pitch-rate dynamics driven by the rotor speeds
// of the motor model (recorded commands, identified tau_m), predicting deflections, pitch rate and specific force over
// one window.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <cmath>
#include <vector>

#include "identification/robust_residual.h"
#include "model/arm_dynamics.h"
#include "model/rk4.h"

namespace birotor {

// Residual layout per sample.
enum FreeArmResidualIndex : int {
  kResB1 = 0,      // strain gauge arm 1
  kResB2 = 1,      // strain gauge arm 2
  kResGyro = 2,    // IMU pitch rate
  kResAccelX = 3,  // IMU specific force, body x
  kResAccelZ = 4,  // IMU specific force, body z
};
constexpr int kFreeArmResidualsPerSample = 5;

// One window of strain samples j = 0..N-1 with rotor speeds (telemetry) and,
// when present, IMU at the same times. From the window's own initial state
// x_0 = (phi_dot, b1, b2, b1_dot, b2_dot) the model
//   x_dot = FreeArmDerivative(k, d; x, f1, f2),  f_i = c_T omega_i^2
// (thesis eq. 3.14, arm_dynamics.h) is integrated with RK4 (`substeps` per
// interval, omega linear between samples), and
//   r_j = [b1_meas - b1, b2_meas - b2] / sigma_b,
//         (gyro_meas - phi_dot) / sigma_gyro,
//         (a_meas - a_model(x_j, f_j)) / sigma_a                    [1, whitened]
// each passed through HuberResidual. A missing measurement (NaN) gives a zero residual. Parameters are ratios to
// their scales: k = theta_k k_scale, d = theta_d d_scale, c_T = theta_c c_scale,
// m_p = theta_m m_scale.
struct FreeArmWindowResidual {
  struct Sample {
    double dt_s;               // time to the next sample [s] (unused for the last)
    double omega_rad_s[2];     // rotor speeds (motor model from the commands) [rad/s]
    double deflection_rad[2];  // strain gauges [rad]
    double gyro_rad_s;         // pitch rate, NaN when not used [rad/s]
    double accel_m_s2[2];      // specific force body x, z, NaN when not used [m/s^2]
  };
  struct Scales {
    double stiffness_n_m_rad;
    double damping_n_m_s_rad;
    double thrust_coeff_n_s2_rad2;
    double tip_mass_kg;
  };
  struct Noise {
    double strain_rad;
    double gyro_rad_s;
    double accel_m_s2;
    double huber;  // Huber threshold on whitened residuals [sigma]
  };

  FreeArmWindowResidual(const VehicleParams& known, std::vector<Sample> samples, const Noise& noise, int substeps,
                        const Scales& scales)
      : known_(known), samples_(std::move(samples)), noise_(noise), substeps_(substeps), scales_(scales) {}

  template <typename T>
  bool operator()(const T* k_ratio, const T* d_ratio, const T* thrust_ratio, const T* tip_mass_ratio, const T* state0,
                  T* residual) const {
    const double c = noise_.huber;
    Integrate<T>(k_ratio[0], d_ratio[0], thrust_ratio[0], tip_mass_ratio[0], state0,
                 [&](size_t j, const FreeArmState<T>& x, const T& k, const T& d, const T& c_t, const T& mp) {
                   const Sample& m = samples_[j];
                   T* r = residual + kFreeArmResidualsPerSample * j;
                   r[kResB1] = HuberResidual(T((m.deflection_rad[0] - x(kFreeB1)) / noise_.strain_rad), c);
                   r[kResB2] = HuberResidual(T((m.deflection_rad[1] - x(kFreeB2)) / noise_.strain_rad), c);
                   r[kResGyro] = std::isfinite(m.gyro_rad_s)
                                     ? HuberResidual(T((m.gyro_rad_s - x(kFreePhiDot)) / noise_.gyro_rad_s), c)
                                     : T(0.0);
                   if (std::isfinite(m.accel_m_s2[0]) && std::isfinite(m.accel_m_s2[1])) {
                     const T f1 = c_t * (m.omega_rad_s[0] * m.omega_rad_s[0]);
                     const T f2 = c_t * (m.omega_rad_s[1] * m.omega_rad_s[1]);
                     Eigen::Matrix<T, 2, 1> specific_force;
                     FreeArmDerivative<T>(known_, k, d, mp, x, f1, f2, &specific_force);
                     r[kResAccelX] = HuberResidual(T((m.accel_m_s2[0] - specific_force(0)) / noise_.accel_m_s2), c);
                     r[kResAccelZ] = HuberResidual(T((m.accel_m_s2[1] - specific_force(1)) / noise_.accel_m_s2), c);
                   } else {
                     r[kResAccelX] = T(0.0);
                     r[kResAccelZ] = T(0.0);
                   }
                 });
    return true;
  }

  // Model state at every sample time of the window (for plots), with the
  // fitted ratios and initial state.
  std::vector<FreeArmState<double>> Predict(double k_ratio, double d_ratio, double thrust_ratio, double tip_mass_ratio,
                                            const double* state0) const {
    std::vector<FreeArmState<double>> states(samples_.size());
    Integrate<double>(k_ratio, d_ratio, thrust_ratio, tip_mass_ratio, state0,
                      [&](size_t j, const FreeArmState<double>& x, double, double, double, double) { states[j] = x; });
    return states;
  }

  const std::vector<Sample>& samples() const { return samples_; }

 private:
  // RK4 over the window from state0; visit(j, x_j, k, d, c_T, m_p) at every sample.
  template <typename T, class Visit>
  void Integrate(const T& k_ratio, const T& d_ratio, const T& thrust_ratio, const T& tip_mass_ratio, const T* state0,
                 const Visit& visit) const {
    using State = FreeArmState<T>;
    const T k = k_ratio * scales_.stiffness_n_m_rad;
    const T d = d_ratio * scales_.damping_n_m_s_rad;
    const T c_t = thrust_ratio * scales_.thrust_coeff_n_s2_rad2;
    const T mp = tip_mass_ratio * scales_.tip_mass_kg;
    State x;
    for (int i = 0; i < kFreeArmStateSize; ++i) x(i) = state0[i];
    // f_i = c_T omega_i^2 with omega linear between samples.
    auto forces = [&](const Sample& a, const Sample& b, double alpha, T* f1, T* f2) {
      const double w1 = a.omega_rad_s[0] + alpha * (b.omega_rad_s[0] - a.omega_rad_s[0]);
      const double w2 = a.omega_rad_s[1] + alpha * (b.omega_rad_s[1] - a.omega_rad_s[1]);
      *f1 = c_t * (w1 * w1);
      *f2 = c_t * (w2 * w2);
    };
    for (size_t j = 0; j < samples_.size(); ++j) {
      if (j > 0) {
        const Sample& s0 = samples_[j - 1];
        const Sample& s1 = samples_[j];
        const double h = s0.dt_s / substeps_;
        for (int s = 0; s < substeps_; ++s) {
          const double a0 = static_cast<double>(s) / substeps_;
          const double a1 = static_cast<double>(s + 1) / substeps_;
          // Forces at the start, middle and end of the substep (Rk4Stage order).
          T force1[3], force2[3];
          forces(s0, s1, a0, &force1[0], &force2[0]);
          forces(s0, s1, 0.5 * (a0 + a1), &force1[1], &force2[1]);
          forces(s0, s1, a1, &force1[2], &force2[2]);
          x = Rk4Step(x, h, [&](const State& y, Rk4Stage stage) {
            const int at = static_cast<int>(stage);
            return FreeArmDerivative<T>(known_, k, d, mp, y, force1[at], force2[at]);
          });
        }
      }
      visit(j, x, k, d, c_t, mp);
    }
  }

 public:
  // *functor (optional) keeps a view of the functor, owned by the cost function.
  static ceres::CostFunction* Create(const VehicleParams& known, std::vector<Sample> samples, const Noise& noise,
                                     int substeps, const Scales& scales,
                                     const FreeArmWindowResidual** functor = nullptr) {
    const int n = kFreeArmResidualsPerSample * static_cast<int>(samples.size());
    auto* residual = new FreeArmWindowResidual(known, std::move(samples), noise, substeps, scales);
    if (functor != nullptr) *functor = residual;
    return new ceres::AutoDiffCostFunction<FreeArmWindowResidual, ceres::DYNAMIC, 1, 1, 1, 1, kFreeArmStateSize>(
        residual, n);
  }

 private:
  const VehicleParams known_;  // m, m_p, L, J (k, d, c_T are parameters)
  const std::vector<Sample> samples_;
  const Noise noise_;
  const int substeps_;
  const Scales scales_;
};

}  // namespace birotor
