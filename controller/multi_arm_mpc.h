// The model predictive controller with N rotor speed inputs, as a pure library
// (no LCM, no logging): each solve linearises the N-rotor prediction model
// (controller/multi_arm_mpc_model.h) about the measured body state, the
// rotor-speed estimate and the command in force, solves the condensed QP
// (controller/mpc_qp.h, the birotor's QP too) on the reference samples over the horizon
// and checks the answer. A vehicle whose allocation spans F_x, F_z and the
// torque (N >= 3, model/vehicle_description.h ControlledAxesMargin) is planned
// level: tilt reference 0, the lateral reference tracked through F_x (or
// about a tilted hover the caller gives, MultiArmHoverBase); a
// birotor (N = 2) tilts for F_x as controller/mpc_controller.h does. On a
// failed, late or bad solve the command is the documented fallback (Solve).
// The birotor's product MPC stays controller/mpc_controller.h (the same QP);
// this one flies in MultiArmController's mode mpc, the N-rotor lock-step loop
// (evaluation/multi_arm_closed_loop.h), docs/mpc.md.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "controller/mpc_controller.h"
#include "controller/mpc_params.h"
#include "controller/mpc_qp.h"
#include "controller/multi_arm_mpc_model.h"
#include "controller/position_attitude_law.h"
#include "controller/reference_point.h"
#include "controller/wrench_allocation.h"
#include "model/vehicle_description.h"

namespace birotor {

struct MultiArmMpcResult {
  // N rotor speed commands [rad/s]: the plan's first when solved, else the
  // fallback; always finite and within [0, omega_max].
  MultiArmMpcInputs omega_cmd_rad_s;
  bool solved = false;                             // the plan was sent (outcome kSolved)
  MpcOutcome outcome = MpcOutcome::kSolverFailed;  // why not, when not
  double solve_time_s = 0.0;                       // wall time of linearise, condense, solve, check [s]
  double solve_cpu_s = 0.0;                        // this thread's CPU time over the same [s]
  int iterations = 0;                              // alglib's (MpcQpSolution::iterations)
  double tilt_slack_rad = 0.0;                     // how far the plan exceeds the tilt limit [rad]
};

// The hover a fully-actuated plan is made about: its tilt and the thrusts
// that hold it there (MultiArmLaw's base: a tilted hover when a rotor is too
// weak for a level one, docs/controller.md "Spare rotors").
struct MultiArmHoverBase {
  double tilt_rad = 0.0;      // phi_b [rad]
  ArmForces<double> force_n;  // f_b, N entries [N]
};

class MultiArmMpc {
 public:
  // The description must be plausible (PlausibilityProblems empty).
  MultiArmMpc(const VehicleDescription& vehicle, const MpcParams& params);

  // One solve from the measured body state (world frame) and the rotor-speed
  // estimate (Advance). reference[k] is the reference at (k + 1) step_s from
  // now (k = 0 .. horizon_steps - 1; fewer samples: the last one is held;
  // ExtrapolateReference fills them from one point). efficiency: e_i of each
  // rotor (N entries; FORCE's thrust_scale or 1). last_command_rad_s: the
  // command in force (N entries), the rate limit's origin; period_s: the time
  // to the next solve [s]. Fallback when the solve fails, comes late (MpcParams
  // deadline_s / deadline_clock), is non-finite or infeasible, or the
  // reference is empty: each rotor's last command clamped to [0, omega_max],
  // or where it is not finite its hover speed with its efficiency. base: the
  // hover a fully-actuated vehicle plans about (null: the level hover
  // f_hover; ignored for a vehicle that tilts to move). No allocation in our
  // code (alglib allocates inside its solver).
  MultiArmMpcResult Solve(const BodyState& measured, const std::vector<ReferencePoint>& reference,
                          const MultiArmMpcInputs& efficiency, const MultiArmMpcInputs& last_command_rad_s,
                          double period_s, const MultiArmHoverBase* base = nullptr);
  // After every command sent, held for dt_s [s]: the motor lag run on it
  // (model/plant.h MotorStep per rotor with its tau_m,i), the rotor speeds the
  // next solve starts from (the controller does not measure them).
  void Advance(const MultiArmMpcInputs& omega_cmd_rad_s, double dt_s);

  // The point extrapolated over the horizon, p + v t + a t^2 / 2 at t = (k + 1)
  // step_s, as controller/mpc_controller.cc does; horizon->size() samples
  // (no allocation when the vector is already that long).
  static void ExtrapolateReference(const ReferencePoint& now, double step_s, std::vector<ReferencePoint>* horizon);
  // The options a vehicle plans with: fully actuated, the tilt and pitch rate
  // weights are MpcParams level_tilt_weight_1_rad2 and
  // level_pitch_rate_weight_s2_rad2 (its tilt reference is 0); otherwise params.
  static MpcParams PlanningParams(const MpcParams& params, bool fully_actuated);
  // The terminal weight P: the discrete Riccati solution of the hover model
  // with the stage weights and R = input weight x I_N.
  static MultiArmMpcStateMatrix TerminalWeight(const MultiArmMpcModel& model, const MpcParams& params);

  // Rotor speeds [rad/s] that make the reference acceleration a (world
  // frame) with efficiencies e. Fully actuated (MultiArmControlModeFor):
  // f = f_hover + A^+ [m a_x, m a_z, 0] at zero tilt, m the total mass, by
  // controller/wrench_allocation.h's WrenchAllocator (its pseudo-inverse and
  // saturation priority); about a tilted base (phi_b != 0)
  // f = f_b + A^+ (R(phi_b)^T m (a + g e_z) - m g [sin phi_b, cos phi_b], 0)
  // (body frame, MultiArmLaw's wrench); otherwise f_i = f_hover,i |[a_x,
  // max(g + a_z, 0.1 g)]| / g (the birotor MPC's feed-forward). omega_i =
  // sqrt(max(f_i, 0) / (e_i c_T,i)), at most omega_max. base: null for the
  // level hover.
  MultiArmMpcInputs FeedForward(const Eigen::Vector2d& acceleration_m_s2, const MultiArmMpcInputs& efficiency,
                                const MultiArmHoverBase* base = nullptr) const;
  // The tilt the reference acceleration needs [rad]: the base's phi_b (0
  // without one) when fully actuated, atan2(-a_x, max(g + a_z, 0.1 g))
  // within +-max_tilt_rad otherwise.
  double ReferenceTilt(const Eigen::Vector2d& acceleration_m_s2, const MultiArmHoverBase* base = nullptr) const;

  bool fully_actuated() const { return fully_actuated_; }
  int rotors() const { return model_.rotors(); }
  const MultiArmMpcModel& model() const { return model_; }
  const MpcQp& qp() const { return qp_; }
  const MultiArmMpcInputs& rotor_speed_estimate_rad_s() const { return omega_estimate_rad_s_; }

 private:
  void FillData(const BodyState& measured, const std::vector<ReferencePoint>& reference,
                const MultiArmMpcInputs& efficiency, const MultiArmMpcInputs& last_command_rad_s, double period_s,
                const MultiArmHoverBase* base);
  MultiArmMpcInputs Fallback(const MultiArmMpcInputs& efficiency, const MultiArmMpcInputs& last_command_rad_s) const;

  VehicleDescription vehicle_;
  bool fully_actuated_ = false;
  MpcParams params_;  // as given, with the level_* weights in place for a fully-actuated vehicle
  MultiArmMpcModel model_;
  MpcQp qp_;
  MpcQpData data_;
  WrenchAllocator allocator_;  // the feed-forward thrusts of a fully-actuated vehicle
  MultiArmMpcInputs omega_estimate_rad_s_;
};

}  // namespace birotor
