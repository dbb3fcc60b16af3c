// Jacobian linearization of the birotor about an operating point (thesis
// section 3.3.4, eq. 3.28-3.34), the augmented system with the rotor forces as
// states (thesis eq. 4.1-4.2), and the arm modes.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "model/birotor_dynamics.h"
#include "model/equilibrium.h"

namespace birotor {

constexpr int kMechStateSize = 10;  // x = [q; v]
constexpr int kAugStateSize = 12;   // x~ = [q; v; f1; f2]
enum AugmentedIndex : int { kAugForce1 = 10, kAugForce2 = 11 };

using MechMatrix = Eigen::Matrix<double, kMechStateSize, kMechStateSize>;
using MechInputMatrix = Eigen::Matrix<double, kMechStateSize, 2>;
using AugMatrix = Eigen::Matrix<double, kAugStateSize, kAugStateSize>;

// x_dot = A dx + B du about (q0, v0, f0). A [1/s, 1/s^2 ...], B [1/(kg m), ...].
struct LinearModel {
  MechMatrix a;
  MechInputMatrix b;
};

// Exact Jacobians of [v; M^-1 (tau - C - G)] with respect to x and f (Jets).
LinearModel Linearize(const BirotorParams& p, const Coords<double>& q0, const Coords<double>& v0, double force1_n,
                      double force2_n);

// Linearization at the hover equilibrium of SolveHoverEquilibrium().
LinearModel LinearizeAtHover(const BirotorParams& p);

// Same system in the thesis's coordinates [x, z, phi, b_s, b_d, and rates],
// b_s = b1 + b2, b_d = b1 - b2 (thesis eq. 3.15-3.21): A' = T A T^-1, B' = T B.
LinearModel ToSumDifferenceCoordinates(const LinearModel& model);

// Augmented system of thesis eq. 4.2: [[A, B], [0, 0]], forces as random-walk states.
AugMatrix AugmentWithForces(const LinearModel& model);

// State names of the 12-state augmented system, in order.
const std::vector<std::string>& AugmentedStateNames();

struct Mode {
  double frequency_hz = 0;   // undamped natural frequency |lambda| / 2 pi [Hz]
  double damping_ratio = 0;  // -Re(lambda) / |lambda|
};

// Oscillatory modes of A (one per complex-conjugate pair), by frequency.
std::vector<Mode> OscillatoryModes(const MechMatrix& a);
// The same for a system matrix of any size (the N-arm model).
std::vector<Mode> OscillatoryModes(const Eigen::MatrixXd& a);

}  // namespace birotor
