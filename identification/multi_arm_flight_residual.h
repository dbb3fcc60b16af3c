// Ceres residual of every arm's stiffness k_i and every rotor's thrust
// coefficient c_T,i of a vehicle with N elastic arms in free flight: output
// error of the free body's pitch-rate and arm dynamics driven by the rotor
// speeds of the motor model, predicting every gauge, the pitch rate and the
// specific force over one window. The N-arm counterpart of
// free_arm_residual.h (without its turbulence knots).
#pragma once

#include <ceres/dynamic_autodiff_cost_function.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

#include "identification/robust_residual.h"
#include "model/multi_arm_dynamics.h"
#include "model/rk4.h"
#include "model/vehicle_description.h"

namespace birotor {

// The window state x = [phi_dot, b_1 .. b_N, b_1_dot .. b_N_dot] (1 + 2 N).
inline constexpr int kMaxFlightStateSize = 1 + 2 * kMaxArms;
inline int FlightStateSize(int arm_count) { return 1 + 2 * arm_count; }
inline int FlightDeflectionIndex(int arm) { return 1 + arm; }
inline int FlightRateIndex(int arm_count, int arm) { return 1 + arm_count + arm; }
template <typename T>
using FlightState = Eigen::Matrix<T, Eigen::Dynamic, 1, 0, kMaxFlightStateSize, 1>;

// Residuals per sample: the N gauges, then the IMU's pitch rate and its
// specific force along body x and z.
inline int FlightResidualsPerSample(int arm_count) { return arm_count + 3; }
inline int FlightGyroResidual(int arm_count) { return arm_count; }

// One window of strain samples j = 0..M-1 with the rotor speeds (motor model)
// and, when present, the IMU at the same times. From the window's own initial
// state x_0 the free body
//   [phi_ddot, b_ddot] = rows phi, b of M^-1 (tau - C - G)   (multi_arm_dynamics.h)
// evaluated at phi = 0 and zero body velocity: in uniform gravity G = g M e_z
// only accelerates z, and the plane has no preferred direction without it, so
// these rows depend on neither x, z, phi nor the body velocity. The hinge
// springs are the fitted k_i (G_b_i += (k_i - k_file,i) b_i, the description's
// spring removed), the forces f_i = c_T,i omega_i^2 (omega linear between
// samples), RK4 with `substeps` per interval. Then
//   r_j = [(b_i,meas - b_i) / sigma_b ..., (gyro - phi_dot) / sigma_gyro,
//          (a_meas - [x_ddot, z_ddot + g]) / sigma_a]                  [1, whitened]
// each through HuberResidual; the specific force at phi = 0 is the body
// frame's (the accelerometer's) at any phi. A missing measurement (NaN) gives
// a zero residual. Parameters are ratios to the description's values:
// k_i = theta_k,i k_file,i, c_T,i = theta_c,i c_T,file,i, m_p,i = theta_m,i
// m_p,file,i (the terms are linear in each m_p,i). The damping d_i is the
// description's.
class MultiArmFlightWindowResidual {
 public:
  struct Sample {
    double dt_s = 0.0;                              // time to the next sample [s] (unused for the last)
    std::array<double, kMaxArms> omega_rad_s{};     // rotor speeds (motor model from the commands) [rad/s]
    std::array<double, kMaxArms> deflection_rad{};  // gauges through the file's calibration [rad]
    double gyro_rad_s = 0.0;                        // pitch rate, NaN when not used [rad/s]
    std::array<double, 2> accel_m_s2{};             // specific force body x, z, NaN when not used [m/s^2]
  };
  struct Noise {
    double strain_rad;
    double gyro_rad_s;
    double accel_m_s2;
    double huber;  // Huber threshold on whitened residuals [sigma]
  };
  // Jet width: k_i, c_T,i, m_p,i and x_0 of a trirotor (16) in one pass.
  static constexpr int kStride = 16;

  // fit_tip_mass: m_p,i enters through its ratio block (N + 1 evaluations
  // of the terms per derivative); otherwise the ratio blocks are ignored
  // (hold them constant) and m_p,i is the description's.
  MultiArmFlightWindowResidual(const VehicleDescription& vehicle, std::vector<Sample> samples, const Noise& noise,
                               int substeps, bool fit_tip_mass)
      : vehicle_(vehicle), samples_(std::move(samples)), noise_(noise), substeps_(substeps) {
    for (int i = 0; fit_tip_mass && i < vehicle.arm_count; ++i) {
      without_tip_.push_back(vehicle);
      without_tip_.back().arms[static_cast<size_t>(i)].tip_mass_kg = 0.0;
    }
  }

  // The vehicle parameters of one evaluation: k_i [N m/rad], c_T,i
  // [N s^2/rad^2] and the tip-mass ratios m_p,i / m_p,file,i [1].
  template <typename T>
  struct Parameters {
    ArmForces<T> stiffness, thrust_coeff, tip_mass_ratio;
  };

  // parameters: k ratios (N blocks of 1), c_T ratios (N), m_p ratios (N), x_0.
  template <typename T>
  bool operator()(T const* const* parameters, T* residual) const {
    const int n = vehicle_.arm_count;
    Parameters<T> p{ArmForces<T>(n), ArmForces<T>(n), ArmForces<T>(n)};
    for (int i = 0; i < n; ++i) {
      const ArmDescription& arm = vehicle_.arms[static_cast<size_t>(i)];
      p.stiffness(i) = parameters[i][0] * arm.stiffness_n_m_rad;
      p.thrust_coeff(i) = parameters[n + i][0] * arm.thrust_coeff_n_s2_rad2;
      p.tip_mass_ratio(i) = parameters[2 * n + i][0];
    }
    FlightState<T> x(FlightStateSize(n));
    for (int i = 0; i < FlightStateSize(n); ++i) x(i) = parameters[3 * n][i];
    const int per_sample = FlightResidualsPerSample(n);
    for (size_t j = 0; j < samples_.size(); ++j) {
      if (j > 0) x = Step<T>(x, p, samples_[j - 1], samples_[j]);
      SampleResiduals<T>(samples_[j], x, p, Forces<T>(p.thrust_coeff, samples_[j], samples_[j], 0.0),
                         residual + per_sample * static_cast<int>(j));
    }
    return true;
  }

  // d x / dt of the window state and the specific force [m/s^2] (body x, z)
  // at x under the forces f [N] (header comment).
  template <typename T>
  FlightState<T> Derivative(const FlightState<T>& x, const Parameters<T>& p, const ArmForces<T>& force_n,
                            Eigen::Matrix<T, 2, 1>* specific_force) const {
    const int n = vehicle_.arm_count;
    MultiCoords<T> q = MultiCoords<T>::Zero(CoordinateCount(vehicle_));
    MultiCoords<T> v = MultiCoords<T>::Zero(CoordinateCount(vehicle_));
    v(kPhi) = x(0);
    for (int i = 0; i < n; ++i) {
      q(DeflectionIndex(i)) = x(FlightDeflectionIndex(i));
      v(DeflectionIndex(i)) = x(FlightRateIndex(n, i));
    }
    const MultiArmTerms<T> file = ComputeMultiArmTerms<T>(vehicle_, q, v, force_n);
    MultiArmTerms<T> terms = file;
    for (int i = 0; i < n; ++i) {
      terms.gravity_spring(DeflectionIndex(i)) +=
          (p.stiffness(i) - vehicle_.arms[static_cast<size_t>(i)].stiffness_n_m_rad) * q(DeflectionIndex(i));
    }
    // m_p,i enters M, C and G linearly: its share is terms(file) minus terms
    // with that tip mass zero, scaled by theta_m,i - 1.
    for (size_t i = 0; i < without_tip_.size(); ++i) {
      const MultiArmTerms<T> rest = ComputeMultiArmTerms<T>(without_tip_[i], q, v, force_n);
      const T extra = p.tip_mass_ratio(static_cast<int>(i)) - 1.0;
      terms.mass += extra * MultiCoordMatrix<T>(file.mass - rest.mass);
      terms.coriolis += extra * MultiCoords<T>(file.coriolis - rest.coriolis);
      terms.gravity_spring += extra * MultiCoords<T>(file.gravity_spring - rest.gravity_spring);
    }
    const MultiCoords<T> acceleration = SolveMultiArmMassMatrix<T>(
        terms.mass, MultiCoords<T>(terms.generalized_thrust - terms.coriolis - terms.gravity_spring));
    FlightState<T> rate(FlightStateSize(n));
    rate(0) = acceleration(kPhi);
    for (int i = 0; i < n; ++i) {
      rate(FlightDeflectionIndex(i)) = v(DeflectionIndex(i));
      rate(FlightRateIndex(n, i)) = acceleration(DeflectionIndex(i));
    }
    if (specific_force != nullptr) {
      (*specific_force)(0) = acceleration(kX);
      (*specific_force)(1) = acceleration(kZ) + vehicle_.gravity_m_s2;
    }
    return rate;
  }

  const std::vector<Sample>& samples() const { return samples_; }

  // The cost function (Ceres' dynamic autodiff) with its parameter blocks.
  static ceres::CostFunction* Create(const VehicleDescription& vehicle, std::vector<Sample> samples, const Noise& noise,
                                     int substeps, bool fit_tip_mass) {
    const int n = vehicle.arm_count;
    const int residuals = FlightResidualsPerSample(n) * static_cast<int>(samples.size());
    auto* cost = new ceres::DynamicAutoDiffCostFunction<MultiArmFlightWindowResidual, kStride>(
        new MultiArmFlightWindowResidual(vehicle, std::move(samples), noise, substeps, fit_tip_mass));
    for (int block = 0; block < 3 * n; ++block) cost->AddParameterBlock(1);
    cost->AddParameterBlock(FlightStateSize(n));
    cost->SetNumResiduals(residuals);
    return cost;
  }

 private:
  // f_i = c_T,i omega_i^2 with omega a fraction alpha from a to b.
  template <typename T>
  ArmForces<T> Forces(const ArmForces<T>& c_t, const Sample& a, const Sample& b, double alpha) const {
    ArmForces<T> f(vehicle_.arm_count);
    for (int i = 0; i < vehicle_.arm_count; ++i) {
      const size_t r = static_cast<size_t>(i);
      const double w = a.omega_rad_s[r] + alpha * (b.omega_rad_s[r] - a.omega_rad_s[r]);
      f(i) = c_t(i) * (w * w);
    }
    return f;
  }

  // RK4 from sample a to sample b in `substeps_` steps.
  template <typename T>
  FlightState<T> Step(FlightState<T> x, const Parameters<T>& p, const Sample& a, const Sample& b) const {
    const ArmForces<T>& c_t = p.thrust_coeff;
    const double h = a.dt_s / substeps_;
    for (int s = 0; s < substeps_; ++s) {
      const double a0 = static_cast<double>(s) / substeps_, a1 = static_cast<double>(s + 1) / substeps_;
      const ArmForces<T> forces[3] = {Forces<T>(c_t, a, b, a0), Forces<T>(c_t, a, b, 0.5 * (a0 + a1)),
                                      Forces<T>(c_t, a, b, a1)};  // Rk4Stage order: start, middle, end
      x = Rk4Step(x, h, [&](const FlightState<T>& y, Rk4Stage stage) {
        return Derivative<T>(y, p, forces[static_cast<int>(stage)], nullptr);
      });
    }
    return x;
  }

  template <typename T>
  void SampleResiduals(const Sample& m, const FlightState<T>& x, const Parameters<T>& p, const ArmForces<T>& force_n,
                       T* r) const {
    const int n = vehicle_.arm_count;
    const double c = noise_.huber;
    for (int i = 0; i < n; ++i) {
      const double measured = m.deflection_rad[static_cast<size_t>(i)];
      r[i] = std::isfinite(measured) ? HuberResidual(T((measured - x(FlightDeflectionIndex(i))) / noise_.strain_rad), c)
                                     : T(0.0);
    }
    const int gyro = FlightGyroResidual(n);
    r[gyro] = std::isfinite(m.gyro_rad_s) ? HuberResidual(T((m.gyro_rad_s - x(0)) / noise_.gyro_rad_s), c) : T(0.0);
    r[gyro + 1] = r[gyro + 2] = T(0.0);
    if (std::isfinite(m.accel_m_s2[0]) && std::isfinite(m.accel_m_s2[1])) {
      Eigen::Matrix<T, 2, 1> specific_force;
      Derivative<T>(x, p, force_n, &specific_force);
      r[gyro + 1] = HuberResidual(T((m.accel_m_s2[0] - specific_force(0)) / noise_.accel_m_s2), c);
      r[gyro + 2] = HuberResidual(T((m.accel_m_s2[1] - specific_force(1)) / noise_.accel_m_s2), c);
    }
  }

  const VehicleDescription vehicle_;  // geometry, masses, d_i (k_i, c_T,i are parameters)
  const std::vector<Sample> samples_;
  const Noise noise_;
  const int substeps_;
  std::vector<VehicleDescription> without_tip_;  // fit_tip_mass: the description with m_p,i = 0, per arm
};

}  // namespace birotor
