// Gain of the discrete Luenberger observer on the N-arm linear force model
// (estimator/multi_arm_linear_model.h) by pole placement: the design of
// estimator/luenberger_gain.h for any described vehicle, which it reproduces
// for the birotor description. Filter form, x+ = A_d x, then the gyro
// x = x+ + L_g (y_g - phi_dot+), then the gauges x = x + L (y - C x):
//   e[k+1] = (I - L C) (I - L_g C_g) A_d e[k].
// L acts on the 3N strain-observable states only and L_g on phi_dot only.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <vector>

#include "estimator/estimator_config.h"
#include "estimator/multi_arm_linear_model.h"

namespace birotor {

struct MultiArmObserverGains {
  Eigen::MatrixXd strain;  // L, (3N + 1) x N [rad/rad, (rad/s)/rad, N/rad]
  Eigen::VectorXd gyro;    // L_g, the phi_dot row only [1]
};

// The arm channels: the modes of the arm block A_bb = d b_ddot / d b (its
// eigenvectors V, channel deflection m = V^-1 b, each row scaled to a largest
// entry of 1), each with the force combination that drives it, g = T_f f,
// T_f = rows of V^-1 A_bf scaled the same way. For the birotor: b1 + b2 with
// f1 - f2, and b1 - b2 with f1 + f2 (luenberger_gain.h), up to scale.
struct MultiArmObserverChannels {
  Eigen::MatrixXd deflection_transform;  // T_b, N x N: m = T_b b [1]
  Eigen::MatrixXd force_transform;       // T_f, N x N: g = T_f f [1]
  Eigen::VectorXd arm_frequency_rad_s;   // w_n of each channel's arm pair (continuous) [rad/s]
};
MultiArmObserverChannels MultiArmArmChannels(const MultiArmLinearForceModel& model);

// Discrete poles, channel by channel (the arm pair exp(s T), s = w_n (-zeta
// +- j sqrt(1 - zeta^2)), then the force pole exp(-2 pi force_bandwidth_hz
// T)), and last the phi_dot pole, the same as the force pole.
std::vector<std::complex<double>> DesiredMultiArmObserverPoles(const MultiArmLinearForceModel& model,
                                                               const LuenbergerOptions& options);

// L and L_g. L by eigenstructure assignment on the scaled strain block (the
// pair (A_d, C A_d), filter form): channel j's poles get left eigenvectors
// u = (A_d^T - z I)^-1 (C A_d)^T T_b,j^T, and U^T L = W^T. Where the channels
// decouple (the birotor: mirror symmetry) this is the birotor's Ackermann
// gain per channel; where they do not (the trirotor: the arms' gravity terms
// differ with their angle) the same poles are placed on the coupled system.
// Throws std::invalid_argument if the arm modes are not real or the options
// are out of range (luenberger: force_bandwidth_hz, arm_damping_ratio).
MultiArmObserverGains PlaceMultiArmObserverPoles(const MultiArmLinearForceModel& model,
                                                 const LuenbergerOptions& options);

// The error matrix (I - L C) (I - L_g C_g) A_d (for the stability check).
Eigen::MatrixXd MultiArmObserverErrorMatrix(const MultiArmLinearForceModel& model, const MultiArmObserverGains& gains);

}  // namespace birotor
