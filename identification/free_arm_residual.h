// Ceres residual of stiffness, damping, thrust coefficient and tip mass in
// free flight: output error of the arm and pitch-rate dynamics driven by the
// rotor speeds of the motor model (recorded commands, identified tau_m) and
// the window's own rotor turbulence, predicting deflections, pitch rate and
// specific force over one window; plus the turbulence's Gauss-Markov prior.
#pragma once

#include <ceres/dynamic_autodiff_cost_function.h>
#include <ceres/normal_prior.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "identification/robust_residual.h"
#include "model/arm_dynamics.h"
#include "model/rk4.h"
#include "samples/rotor_count.h"

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

// One window of strain samples j = 0..N-1 with rotor speeds (motor model)
// and, when present, IMU at the same times. From the window's own initial
// state x_0 = (phi_dot, b1, b2, b1_dot, b2_dot) the model
//   x_dot = FreeArmDerivative(k, d, m_p; x, f1, f2),
//   f_i = c_T omega_i^2 (1 + eta_i(t))
// (thesis eq. 3.14, arm_dynamics.h; mu_i = 1 + eta_i of reference-vehicle.md)
// is integrated with RK4 (`substeps` per interval, omega and eta linear
// between samples), and
//   r_j = [b1_meas - b1, b2_meas - b2] / sigma_b,
//         (gyro_meas - phi_dot) / sigma_gyro,
//         (a_meas - a_model(x_j, f_j)) / sigma_a                    [1, whitened]
// each passed through HuberResidual. A missing measurement (NaN) gives a zero
// residual. Parameters are ratios to their scales: k = theta_k k_scale,
// d = theta_d d_scale, c_T = theta_c c_scale, m_p = theta_m m_scale.
//
// The rotor turbulence eta_i (relative thrust, a Gauss-Markov process of
// 0.1 s correlation time on the reference vehicle) is the one input the
// sensors do not record. Left out, it drives the model with about 1 % of the
// thrust as correlated force noise: on flight_id the gyro residual is then
// 6.6 sigma and m_p comes out 5 % high. Here eta_i is piecewise linear in
// time with knots at samples spaced about `turbulence_knot_s` apart, the knot
// values being a window parameter block [eta_1 knots, eta_2 knots] under the
// process's own prior (TurbulencePrior). `turbulence_knot_s` = 0 holds eta
// at 0 (no knot block).
struct FreeArmWindowResidual {
  struct Sample {
    double dt_s;                            // time to the next sample [s] (unused for the last)
    double omega_rad_s[kBirotorRotors];     // rotor speeds (motor model from the commands) [rad/s]
    double deflection_rad[kBirotorRotors];  // strain gauges [rad]
    double gyro_rad_s;                      // pitch rate, NaN when not used [rad/s]
    double accel_m_s2[2];                   // specific force body x, z, NaN when not used [m/s^2]
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
  // Jet width of the dynamic autodiff (parameters differentiated per pass):
  // k, c_T, m_p, x_0 and 2 x 7 knots (0.3 s windows, 0.05 s knots) in two passes.
  static constexpr int kStride = 12;

  FreeArmWindowResidual(const BirotorParams& known, std::vector<Sample> samples, const Noise& noise, int substeps,
                        const Scales& scales, double turbulence_knot_s)
      : known_(known), samples_(std::move(samples)), noise_(noise), substeps_(substeps), scales_(scales) {
    PlaceKnots(turbulence_knot_s);
  }

  // Size of the window's knot block: the knots of eta_1, then those of eta_2 (0: no block).
  int KnotBlockSize() const { return 2 * num_knots(); }
  int num_knots() const { return static_cast<int>(knot_sample_.size()); }
  // Times of the knots from the window start [s].
  std::vector<double> KnotTimes() const {
    std::vector<double> t;
    for (int sample : knot_sample_) t.push_back(time_s_[sample]);
    return t;
  }

  // parameters: k, d, c_T, m_p ratios, x_0, then the knot block (if any).
  template <typename T>
  bool operator()(T const* const* parameters, T* residual) const {
    Integrate<T>(
        parameters[0][0], parameters[1][0], parameters[2][0], parameters[3][0], parameters[4],
        num_knots() > 0 ? parameters[5] : nullptr,
        [&](size_t j, const FreeArmState<T>& x, const T& k, const T& d, const T& mp, const T& f1, const T& f2) {
          SampleResiduals<T>(j, x, k, d, mp, f1, f2, residual + kFreeArmResidualsPerSample * j);
        });
    return true;
  }

  // The kFreeArmResidualsPerSample residuals r_j of sample j (above) from
  // the model state x_j, the parameters and the forces f_i at t_j [N].
  template <typename T>
  void SampleResiduals(size_t j, const FreeArmState<T>& x, const T& k, const T& d, const T& mp, const T& f1,
                       const T& f2, T* r) const {
    const double c = noise_.huber;
    const Sample& m = samples_[j];
    r[kResB1] = HuberResidual(T((m.deflection_rad[0] - x(kFreeB1)) / noise_.strain_rad), c);
    r[kResB2] = HuberResidual(T((m.deflection_rad[1] - x(kFreeB2)) / noise_.strain_rad), c);
    r[kResGyro] =
        std::isfinite(m.gyro_rad_s) ? HuberResidual(T((m.gyro_rad_s - x(kFreePhiDot)) / noise_.gyro_rad_s), c) : T(0.0);
    if (std::isfinite(m.accel_m_s2[0]) && std::isfinite(m.accel_m_s2[1])) {
      Eigen::Matrix<T, 2, 1> specific_force;
      FreeArmDerivative<T>(known_, k, d, mp, x, f1, f2, &specific_force);
      r[kResAccelX] = HuberResidual(T((m.accel_m_s2[0] - specific_force(0)) / noise_.accel_m_s2), c);
      r[kResAccelZ] = HuberResidual(T((m.accel_m_s2[1] - specific_force(1)) / noise_.accel_m_s2), c);
    } else {
      r[kResAccelX] = T(0.0);
      r[kResAccelZ] = T(0.0);
    }
  }

  // Model state at every sample time of the window (for plots), with the
  // fitted ratios, initial state and knots (nullptr without knots).
  std::vector<FreeArmState<double>> Predict(double k_ratio, double d_ratio, double thrust_ratio, double tip_mass_ratio,
                                            const double* state0, const double* knots) const {
    std::vector<FreeArmState<double>> states(samples_.size());
    Integrate<double>(
        k_ratio, d_ratio, thrust_ratio, tip_mass_ratio, state0, knots,
        [&](size_t j, const FreeArmState<double>& x, double, double, double, double, double) { states[j] = x; });
    return states;
  }

  const std::vector<Sample>& samples() const { return samples_; }
  const BirotorParams& known() const { return known_; }
  const Scales& scales() const { return scales_; }
  int substeps() const { return substeps_; }
  // eta_i at sample j is (1 - w) knot[s] + w knot[s + 1] of its rotor, s =
  // KnotSegment(j), w = KnotWeight(j) (knots present only).
  int KnotSegment(size_t j) const { return segment_[j]; }
  double KnotWeight(size_t j) const { return weight_[j]; }

  // The cost function with Ceres' dynamic autodiff (the reference of
  // FreeArmWindowCost, free_arm_window_cost.h, which the fits use). *functor
  // (optional) keeps a view of the functor, owned by the cost function.
  static ceres::CostFunction* CreateAutoDiff(const BirotorParams& known, std::vector<Sample> samples,
                                             const Noise& noise, int substeps, const Scales& scales,
                                             double turbulence_knot_s,
                                             const FreeArmWindowResidual** functor = nullptr) {
    const int n = kFreeArmResidualsPerSample * static_cast<int>(samples.size());
    auto* residual = new FreeArmWindowResidual(known, std::move(samples), noise, substeps, scales, turbulence_knot_s);
    if (functor != nullptr) *functor = residual;
    auto* cost = new ceres::DynamicAutoDiffCostFunction<FreeArmWindowResidual, kStride>(residual);
    for (int ratio = 0; ratio < 4; ++ratio) cost->AddParameterBlock(1);
    cost->AddParameterBlock(kFreeArmStateSize);
    if (residual->num_knots() > 0) cost->AddParameterBlock(residual->KnotBlockSize());
    cost->SetNumResiduals(n);
    return cost;
  }

  // Prior of the knots of one window: eta_i is a stationary first-order
  // Gauss-Markov process (std sigma, correlation time tau), so for knots
  // h_j apart with a_j = exp(-h_j / tau)
  //   r_0 = eta_0 / sigma,  r_j = (eta_j - a_j eta_{j-1}) / (sigma sqrt(1 - a_j^2))   [1, whitened]
  // (the exact joint density of the knot values), for each rotor. A
  // ceres::NormalPrior A (knots - 0) over the knot block; nullptr when there
  // are no knots.
  ceres::CostFunction* TurbulencePrior(double turbulence_std, double correlation_time_s) const {
    const int n = num_knots();
    if (n == 0) return nullptr;
    ceres::Matrix a = ceres::Matrix::Zero(2 * n, KnotBlockSize());
    const std::vector<double> t = KnotTimes();
    for (int rotor = 0; rotor < kBirotorRotors; ++rotor) {
      const int row0 = rotor * n, col0 = rotor * n;
      a(row0, col0) = 1.0 / turbulence_std;
      for (int j = 1; j < n; ++j) {
        const double decay = std::exp(-(t[j] - t[j - 1]) / correlation_time_s);
        const double innovation_std = turbulence_std * std::sqrt(1.0 - decay * decay);
        a(row0 + j, col0 + j) = 1.0 / innovation_std;
        a(row0 + j, col0 + j - 1) = -decay / innovation_std;
      }
    }
    return new ceres::NormalPrior(a, ceres::Vector::Zero(KnotBlockSize()));
  }

 private:
  // Knots at samples about knot_s apart (the first and the last sample
  // included); for each sample the knot segment it lies in and its weight.
  void PlaceKnots(double knot_s) {
    const size_t n = samples_.size();
    time_s_.assign(n, 0.0);
    for (size_t j = 1; j < n; ++j) time_s_[j] = time_s_[j - 1] + samples_[j - 1].dt_s;
    segment_.assign(n, 0);
    weight_.assign(n, 0.0);
    if (knot_s <= 0.0 || n < 2) return;
    const double span_s = time_s_.back();
    const int segments = std::max(1, static_cast<int>(std::lround(span_s / knot_s)));
    knot_sample_.push_back(0);
    for (int s = 1; s <= segments; ++s) {
      const double target_s = span_s * s / segments;
      const size_t j = std::lower_bound(time_s_.begin(), time_s_.end(), target_s - 1e-9) - time_s_.begin();
      if (static_cast<int>(j) > knot_sample_.back()) knot_sample_.push_back(static_cast<int>(std::min(j, n - 1)));
    }
    int segment = 0;
    for (size_t j = 0; j < n; ++j) {
      while (segment + 2 < num_knots() && static_cast<int>(j) >= knot_sample_[segment + 1]) ++segment;
      const double t0 = time_s_[knot_sample_[segment]], t1 = time_s_[knot_sample_[segment + 1]];
      segment_[j] = segment;
      weight_[j] = std::clamp((time_s_[j] - t0) / (t1 - t0), 0.0, 1.0);
    }
  }

  // eta of `rotor` at sample j (linear between knots); 0 without knots.
  template <typename T>
  T Turbulence(const T* knot_block, int rotor, size_t j) const {
    if (knot_block == nullptr) return T(0.0);
    const T* knots = knot_block + rotor * num_knots();
    const int s = segment_[j];
    return knots[s] + weight_[j] * (knots[s + 1] - knots[s]);
  }

  // RK4 over the window from x_0 with the knots (nullptr: eta = 0);
  // visit(j, x_j, k, d, m_p, f1_j, f2_j) at every sample.
  template <typename T, class Visit>
  void Integrate(const T& k_ratio, const T& d_ratio, const T& thrust_ratio, const T& tip_mass_ratio, const T* state0,
                 const T* knots, const Visit& visit) const {
    using State = FreeArmState<T>;
    const T k = k_ratio * scales_.stiffness_n_m_rad;
    const T d = d_ratio * scales_.damping_n_m_s_rad;
    const T c_t = thrust_ratio * scales_.thrust_coeff_n_s2_rad2;
    const T mp = tip_mass_ratio * scales_.tip_mass_kg;
    State x;
    for (int i = 0; i < kFreeArmStateSize; ++i) x(i) = state0[i];
    // f_i = c_T omega_i^2 (1 + eta_i) with omega and eta linear between samples.
    T mu_prev[kBirotorRotors], mu_next[kBirotorRotors];
    for (int rotor = 0; rotor < kBirotorRotors; ++rotor) mu_next[rotor] = 1.0 + Turbulence(knots, rotor, 0);
    auto force = [&](const Sample& a, const Sample& b, int rotor, double alpha) {
      const double w = a.omega_rad_s[rotor] + alpha * (b.omega_rad_s[rotor] - a.omega_rad_s[rotor]);
      return c_t * (w * w) * (mu_prev[rotor] + alpha * (mu_next[rotor] - mu_prev[rotor]));
    };
    for (size_t j = 0; j < samples_.size(); ++j) {
      for (int rotor = 0; rotor < kBirotorRotors; ++rotor) {
        mu_prev[rotor] = mu_next[rotor];
        if (j > 0) mu_next[rotor] = 1.0 + Turbulence(knots, rotor, j);
      }
      if (j > 0) {
        const Sample& s0 = samples_[j - 1];
        const Sample& s1 = samples_[j];
        const double h = s0.dt_s / substeps_;
        for (int s = 0; s < substeps_; ++s) {
          const double a0 = static_cast<double>(s) / substeps_;
          const double a1 = static_cast<double>(s + 1) / substeps_;
          const double alphas[3] = {a0, 0.5 * (a0 + a1), a1};  // Rk4Stage order: start, middle, end
          T force1[3], force2[3];
          for (int at = 0; at < 3; ++at) {
            force1[at] = force(s0, s1, 0, alphas[at]);
            force2[at] = force(s0, s1, 1, alphas[at]);
          }
          x = Rk4Step(x, h, [&](const State& y, Rk4Stage stage) {
            const int at = static_cast<int>(stage);
            return FreeArmDerivative<T>(known_, k, d, mp, y, force1[at], force2[at]);
          });
        }
      }
      // Forces at sample j itself (alpha = 1 of the last interval, or mu at j = 0).
      const Sample& m = samples_[j];
      const T f1 = c_t * (m.omega_rad_s[0] * m.omega_rad_s[0]) * mu_next[0];
      const T f2 = c_t * (m.omega_rad_s[1] * m.omega_rad_s[1]) * mu_next[1];
      visit(j, x, k, d, mp, f1, f2);
    }
  }

  const BirotorParams known_;  // m, L, J (k, d, c_T, m_p are parameters)
  const std::vector<Sample> samples_;
  const Noise noise_;
  const int substeps_;
  const Scales scales_;
  std::vector<double> time_s_;    // sample times from the window start [s]
  std::vector<int> knot_sample_;  // sample index of each knot (empty: eta held at 0)
  std::vector<int> segment_;      // per sample: knot segment [knot s, knot s + 1]
  std::vector<double> weight_;    // per sample: position in its segment [0, 1]
};

}  // namespace birotor
