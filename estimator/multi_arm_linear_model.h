// The linear hover model with the rotor forces as states for any described
// vehicle (N = 2 .. kMaxArms arms): the N-arm counterpart of
// estimator/linear_force_model.h, which it reproduces for the birotor
// description. The common model of the N-arm linear Kalman filter and
// Luenberger observer (estimator/multi_arm_linear_estimator.h).
#pragma once

#include <Eigen/Core>

#include "estimator/estimator_config.h"
#include "model/vehicle_description.h"

namespace birotor {

// Named indices of the observable part for N arms, deviations from hover:
// b_1 .. b_N [rad], b_1_dot .. b_N_dot [rad/s], f_1 .. f_N [N], phi_dot
// [rad/s]. For N = 2 the order of LinearIndex (linear_force_model.h).
struct MultiArmLinearLayout {
  static constexpr int Deflection(int arm) { return arm; }
  static constexpr int DeflectionRate(int n, int arm) { return n + arm; }
  static constexpr int Force(int n, int arm) { return 2 * n + arm; }
  static constexpr int PitchRate(int n) { return 3 * n; }
  static constexpr int StateSize(int n) { return 3 * n + 1; }
  // The first 3N states are what the strain gauges alone observe.
  static constexpr int StrainObservableSize(int n) { return 3 * n; }
};

// x_dot = A x + w, y = (b_1 .. b_N) or phi_dot, in physical units, and the
// same system sampled every period_s (the fields of LinearForceModel, sized
// at start-up: 3N + 1 states).
struct MultiArmLinearForceModel {
  int arm_count = 0;
  Eigen::MatrixXd a_continuous;          // observable block of the augmented model [1/s, 1/s^2, rad/(N s^2)]
  Eigen::MatrixXd noise_continuous;      // Q_c: spectral densities of w [unit^2/s]
  Eigen::MatrixXd a_discrete;            // A_d = exp(A period_s)
  Eigen::MatrixXd noise_discrete;        // Q_d (Van Loan)
  Eigen::VectorXd scale;                 // x = diag(scale) x_s makes every block O(1) [unit]
  double period_s = 1e-3;                // 1 / strain rate [s]
  Eigen::VectorXd deflection_hover_rad;  // b_i at hover (SolveMultiArmHover) [rad]
  Eigen::VectorXd force_hover_n;         // f_i at hover [N]
  double force_psd_n2_s = 0;             // Q_c on each force (random walk) [N^2/s]
};

// Builds the model at the hover equilibrium, the steps of
// BuildLinearForceModel on the N-arm model:
// 1. linearise (model/multi_arm_linearization.h) and augment with the forces;
// 2. keep the axes b_i, b_i_dot, f_i and phi_dot, after checking that the
//    others (x, z, phi, x_dot, z_dot) do not drive them (the hidden subspace
//    is A-invariant, so the kept block is exactly the observable part), that
//    phi_dot does not drive the arms, and that the kept block is observable
//    from (b_1 .. b_N, phi_dot) (rank 3N + 1, model/observability.h);
// 3. noise from the EKF's figures: its rate noise on b_i_dot and phi_dot and
//    linear_model.force_psd_n2_s on each force;
// 4. scale (deflection per newton, the fastest arm frequency) and discretise
//    exactly (matrix exponential, Van Loan for Q_d).
// Throws std::invalid_argument (naming the failed check) for a vehicle this
// model does not hold for, or a rate out of range.
MultiArmLinearForceModel BuildMultiArmLinearForceModel(const VehicleDescription& vehicle, const EkfOptions& noise,
                                                       const LinearModelOptions& options);

}  // namespace birotor
