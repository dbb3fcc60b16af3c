// A closed loop of the N-input MPC (controller/multi_arm_mpc.h) on the
// nonlinear plant of any description (model/multi_arm_plant.h: elastic arms,
// motor lag, command clamp), with the MPC on the true body state: the one
// flight the tests and the solve-time benchmark both fly. No sensors, no
// estimator, no transport (the lock-step loop and the product controller
// wire the MPC in elsewhere: MultiArmController in mode mpc).
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "controller/mpc_params.h"
#include "model/vehicle_description.h"

namespace birotor {

struct MultiArmMpcFlightOptions {
  // The reference: a step from hover at the origin to this position (world
  // x, z [m]), held from t = 0, velocity and acceleration 0.
  Eigen::Vector2d target_m = Eigen::Vector2d(1.0, 0.0);
  double duration_s = 4.0;        // flight length [s]
  double plant_step_s = 0.00025;  // RK4 step of the plant: 4 kHz [s]
  // Distance to the target [m] under which the vehicle counts as there
  // (MultiArmMpcFlightResult::settle_s).
  double settle_band_m = 0.05;
  // e_i of the plant's rotors (its thrust scale mu_i) and the ones the MPC
  // plans with (FORCE's estimate in flight) [1]; entries [0, N) are used.
  std::array<double, kMaxArms> plant_efficiency{1, 1, 1, 1, 1, 1};
  std::array<double, kMaxArms> planned_efficiency{1, 1, 1, 1, 1, 1};
};

struct MultiArmMpcFlightResult {
  Eigen::Vector2d final_position_m = Eigen::Vector2d::Zero();  // x, z at the end [m]
  double final_speed_m_s = 0.0;                                // |[x_dot, z_dot]| at the end [m/s]
  double peak_tilt_rad = 0.0;                                  // max |phi| over the flight [rad]
  double peak_x_overshoot_m = 0.0;                             // max (x - target_x) along +x [m]
  double peak_altitude_error_m = 0.0;                          // max |z - target_z| [m]
  // First time after which the body stays within settle_band_m of the
  // target to the end [s]; duration_s when it never does.
  double settle_s = 0.0;
  int solves = 0;
  int fallbacks = 0;  // solves whose command was the fallback
  // Fallbacks by reason (MpcOutcome: solver failed, non-finite, infeasible, late).
  int solver_failed = 0, non_finite = 0, infeasible = 0, late = 0;
  int max_iterations = 0;            // alglib's, over the flight
  std::vector<double> solve_cpu_s;   // per solve, this thread's CPU time [s]
  std::vector<double> solve_wall_s;  // per solve, wall time [s]
};

// Flies the description from hover at the origin (SolveMultiArmHover's
// deflections and speeds) with the MPC at params.rate_hz on the true body
// state (efficiencies as the options say), each command held over its period.
MultiArmMpcFlightResult FlyMultiArmMpc(const VehicleDescription& vehicle, const MpcParams& params,
                                       const MultiArmMpcFlightOptions& options);

}  // namespace birotor
