// Hover equilibrium, Jacobian linearization and arm modes of the N-arm model
// (model/multi_arm_dynamics.h), and the system augmented with the rotor forces
// as states: the N-arm counterparts of equilibrium.h and linearization.h, which
// they reproduce for the birotor description.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "model/linearization.h"
#include "model/vehicle_description.h"

namespace birotor {

// The level (phi = 0), still, deflected vehicle under its hover thrusts.
struct MultiArmHover {
  Eigen::VectorXd allocation_force_n;  // SolveHover's rigid thrusts, the first guess [N]
  Eigen::VectorXd force_n;             // f_i at the equilibrium [N]
  Eigen::VectorXd deflection_rad;      // b_i at the equilibrium [rad]
  double residual = 0;                 // max |tau - G| left on the balanced rows [N, N m]
  bool converged = false;
};

// Hover thrusts and deflections. First guess: the rigid hover of SolveHover
// (model/vehicle_description.h), A f = w_hover with the tip weights' moment
// (least-norm over F_x, F_z and torque; F_z and torque only for N = 2, a
// birotor cannot balance F_x at phi = 0 other than by symmetry), and
// b_i = (l_i f_i - m_p,i g L_i cos alpha_i) / k_i. Then Newton (min-norm
// steps, exact Jet Jacobian) on the static rows tau - G = 0 at q = [0, 0, 0, b], v = 0 for the unknowns (b, f):
// rows x, z, phi, b_1 .. b_N (z, phi, b_1, b_2 for N = 2, as equilibrium.h).
MultiArmHover SolveMultiArmHover(const VehicleDescription& vehicle);

// x_dot = A dx + B df about (q0, v0, f0), x = [q; v] (2n states, n = 3 + N):
// exact Jacobians of [v; M^-1 (tau - C - G)] by Jets. A is 2n x 2n, B is 2n x N.
struct MultiArmLinearModel {
  Eigen::MatrixXd a;
  Eigen::MatrixXd b;
};
MultiArmLinearModel LinearizeMultiArm(const VehicleDescription& vehicle, const Eigen::VectorXd& q0,
                                      const Eigen::VectorXd& v0, const Eigen::VectorXd& force0_n);

// The linearization at SolveMultiArmHover's equilibrium.
MultiArmLinearModel LinearizeMultiArmAtHover(const VehicleDescription& vehicle, const MultiArmHover& hover);

// [[A, B], [0, 0]]: the forces as random-walk (constant) states, thesis eq. 4.2.
Eigen::MatrixXd AugmentMultiArmWithForces(const MultiArmLinearModel& model);

// Names of [q; v; f]: x, z, phi, b1 .. bN, x_dot .. bN_dot, f1 .. fN (for N = 2
// the names of AugmentedStateNames()).
std::vector<std::string> MultiArmStateNames(int arm_count);

}  // namespace birotor
