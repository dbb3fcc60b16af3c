// Which slow vehicle parameters in-flight data determine (issue 27 item 2):
// the hover linearisation augmented with the rotor speeds, the thrust scales
// mu_i and gauge offsets o_i the EKF carries, and the parameters as constant
// states (relative deviations, so the columns are comparable), observed by a
// chosen set of the EKF's measurements; analysed with the balanced staircase
// test of model/observability.h.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "model/birotor_params.h"
#include "model/observability.h"

namespace birotor {

// The measurements of the EKF, as selectable rows.
enum class ParameterMeasurement : int {
  kStrain = 0,         // y_i = s_i b_i + o_i |b_i0| (both gauges)
  kTelemetry = 1,      // omega_1, omega_2
  kGyro = 2,           // phi_dot
  kAccelerometer = 3,  // body-frame specific force a_z
};

// The augmented state: 10 mechanical states, omega_i, mu_i, o_i (in units
// of the hover deflection |b_i0|, so comparable with theta_si), then the
// parameters as relative deviations theta = dp / p: k1, k2 (per-arm
// stiffness), m (body mass), m_p (tip mass), c_T, tau_m, s1, s2 (gauge scales).
constexpr int kParameterAugmentedSize = 24;
constexpr int kFirstParameterState = 16;
const std::vector<std::string>& ParameterAugmentedStateNames();

struct ParameterObservability {
  SubspaceReport report;  // rank, hidden axes, singular values of the 24-state system
  // Parameter (and mu_i, o_i) axes with no component in the hidden subspace:
  // what the flight determines on its own.
  std::vector<std::string> observable_parameters;
  // The combinations c^T (mu, o, theta) the flight determines (c orthogonal
  // to the hidden subspace's mu/o/theta block), in reduced row echelon form
  // ("1.00 mu1 + -1.00 c_T": mu1 - c_T is determined), entries below 0.05
  // left out, and how
  // many there are (12 minus the undetermined dimension).
  std::vector<std::string> determined_combinations;
  int determined = 0;
};

// The linearised augmented system at hover: A (24 x 24) and the rows C of the
// given measurements (Jacobians by central differences of the model of
// model/birotor_dynamics.h; d/dtheta of the parameters).
void LinearizeWithParameters(const BirotorParams& params, const std::vector<ParameterMeasurement>& measured,
                             Eigen::MatrixXd* a, Eigen::MatrixXd* c);

ParameterObservability AnalyzeParameterObservability(const BirotorParams& params,
                                                     const std::vector<ParameterMeasurement>& measured);

}  // namespace birotor
