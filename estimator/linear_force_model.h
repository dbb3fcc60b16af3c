// The thesis's linear hover model with the rotor forces as states (thesis
// eq. 4.2), reduced to its observable part from the strain gauges and the
// gyro (thesis eq. 4.6 plus phi_dot: Kalman decomposition) and discretised at
// the strain rate; the common model of the Luenberger observer and the linear
// Kalman filter.
#pragma once

#include <Eigen/Core>

#include "estimator/estimator_config.h"
#include "model/birotor_params.h"
#include "samples/rotor_count.h"

namespace birotor {

// Named indices of the observable part, deviations from hover.
enum LinearIndex : int {
  kLinDeflection1 = 0,      // b1 - b1_hover [rad]
  kLinDeflection2 = 1,      // b2 - b2_hover [rad]
  kLinDeflectionRate1 = 2,  // b1_dot [rad/s]
  kLinDeflectionRate2 = 3,  // b2_dot [rad/s]
  kLinForce1 = 4,           // f1 - f_hover [N]
  kLinForce2 = 5,           // f2 - f_hover [N]
  kLinPitchRate = 6,        // phi_dot [rad/s]: seen by the gyro only, driven by b1 + b2
};
constexpr int kLinearStateSize = 7;
// The first six states are what the strain gauges alone observe (thesis
// eq. 4.6); phi_dot never drives them (block triangular A).
constexpr int kStrainObservableSize = 6;
constexpr int kLinearOutputSize = 2;  // the two strain gauges
constexpr LinearIndex kLinDeflectionIndex[kBirotorRotors] = {kLinDeflection1, kLinDeflection2};
constexpr LinearIndex kLinForceIndex[kBirotorRotors] = {kLinForce1, kLinForce2};

using LinearState = Eigen::Matrix<double, kLinearStateSize, 1>;
using LinearMatrix = Eigen::Matrix<double, kLinearStateSize, kLinearStateSize>;
using LinearOutputMatrix = Eigen::Matrix<double, kLinearOutputSize, kLinearStateSize>;
using LinearGain = Eigen::Matrix<double, kLinearStateSize, kLinearOutputSize>;
using LinearGyroGain = Eigen::Matrix<double, kLinearStateSize, 1>;
using LinearGyroMatrix = Eigen::Matrix<double, 1, kLinearStateSize>;

// x_dot = A x + w, y = C x + v in physical units (the rows above), and the
// same system sampled every period_s: x[k+1] = A_d x[k] + w_d, w_d ~ N(0, Q_d).
struct LinearForceModel {
  LinearMatrix a_continuous;      // observable block of thesis eq. 4.2 [1/s, 1/s^2, rad/(N s^2)]
  LinearMatrix noise_continuous;  // Q_c: spectral densities of w [unit^2/s]
  LinearMatrix a_discrete;        // A_d = exp(A period_s)
  LinearMatrix noise_discrete;    // Q_d = int_0^T exp(A s) Q_c exp(A^T s) ds (Van Loan)
  LinearOutputMatrix c;           // strain: y = (b1 - b1_hover, b2 - b2_hover) [1]
  LinearGyroMatrix c_gyro;        // gyro: y = phi_dot [1]
  LinearState scale;              // x = diag(scale) x_s makes every block O(1) [unit]
  double period_s = 1e-3;         // 1 / strain rate [s]
  double deflection_hover_rad[kBirotorRotors] = {0, 0};
  double force_hover_n[kBirotorRotors] = {0, 0};
  double force_psd_n2_s = 0;  // Q_c on each force (random walk) [N^2/s]
};

// Builds the model at the hover equilibrium:
// 1. linearise the full model (10 states) and augment it with the forces
//    (thesis eq. 4.2, 12 states);
// 2. find the unobservable subspace from (b1, b2) with the balanced staircase
//    test (estimator/observability.h) and check it is spanned by the state
//    axes x, z, phi and their rates (thesis eq. 4.6), and from (b1, b2,
//    phi_dot) by the same axes but phi_dot; both A-invariant, so the
//    observable part is exactly the block of the seven remaining axes (Kalman
//    decomposition with an orthogonal, axis-aligned basis);
// 3. noise from the EKF's figures: its rate noise on b_i_dot and phi_dot, and
//    on each force the EKF's random walk of mu and its omega noise mapped
//    through f = mu c_T omega^2 at hover: q_f = (c_T w0^2)^2 q_mu + (2 c_T w0)^2 q_w;
// 4. discretise exactly (matrix exponential, Van Loan for Q_d).
// Throws std::invalid_argument if the decomposition is not as above (a vehicle
// for which this model does not hold) or the rate is out of range.
LinearForceModel BuildLinearForceModel(const BirotorParams& params, const EkfOptions& noise,
                                       const LinearModelOptions& options);

}  // namespace birotor
