// Options of the model predictive controller (controller/mpc_controller.h):
// horizon, weights, limits, rate and real-time budget, each with its default
// and the reason for it. Read from the `mpc:` section of config/controller.yaml
// by params/controller_config_yaml.cc.
#pragma once

namespace birotor {

// What a solve's deadline is measured in.
enum class MpcDeadlineClock : int {
  kWall = 0,       // steady clock: a late command is late however it got late (the live daemon)
  kThreadCpu = 1,  // this thread's CPU time: preemption does not count, cache and frequency still do
  kWork = 2,       // the solver's own work count (MpcQpSolution::iterations) against deadline_work:
                   // the same problem is late or not on every machine (the lock-step loop)
};

// The QP algorithm of alglib's minqp used for the condensed problem.
enum class MpcQpAlgorithm : int {
  kDenseIpm = 0,  // primal-dual interior point, dense; no warm start (alglib ignores the start point)
  kBleic = 1,     // active set on L-BFGS steps; warm-started from the shifted previous plan
  kDenseAul = 2,  // augmented Lagrangian with a dense preconditioner; warm-started
};

struct MpcParams {
  // Solve rate [Hz]. 200 Hz, twice the floor: the pitch loop it
  // closes has a bandwidth near 20 rad/s (the cascade's), far below either
  // rate, but a rotor loss is seen one period after it happens, and 5 ms
  // instead of 10 ms of unopposed torque halved the fault's peak tilt with
  // the recovery weights (docs/mpc.md); aggressive tracks at 0.0045 m
  // instead of 0.0063. The slowest solve (p99 ~0.3 ms) leaves the 5 ms
  // period 10x spare.
  double rate_hz = 200.0;
  // Prediction step [s] and number of steps. 20 ms x 20 = 0.4 s: the motor lag
  // (35 ms) spans two steps, the pitch response (~0.15 s) is inside the
  // horizon, the position response (~1 s) is carried by the terminal cost (the
  // discrete Riccati solution at hover). 40 inputs keep the dense QP small.
  double step_s = 0.02;
  int horizon_steps = 20;
  // Move blocking: the commands change only at the starts of this many blocks
  // whose lengths grow along the horizon (block b starts at step
  // round(N (b / B)^2), at least one step after the previous): 1, 2, 4, 6, 7
  // steps for N = 20, B = 5. Early moves stay free, late ones matter only in
  // sum. 11 variables: with 7 blocks (15 variables) the saturated plans of the
  // 70 % loss took p99 1010 us [631, 1631] CPU per solve, with 5 they take
  // ~360 us, at the same tracking (aggressive RMS 0.0064 vs 0.0063 m);
  // without blocking (41 variables) DENSE-IPM took 690 us CPU per solve.
  int input_blocks = 5;
  // The tilt limit is imposed at every this many prediction steps (and the
  // last): every 40 ms, against a pitch response of ~150 ms.
  int tilt_check_every_steps = 2;

  // State weights of the stage cost (per squared unit). Position dominates
  // (what is tracked); velocity damps it; tilt towards the tilt the reference
  // acceleration needs, and a little pitch rate for a smooth attitude.
  // Position 3e3, velocity 1e3: at 1e5 / 3e3 the plan spent tilt on
  // millimetres of position noise in hover (peak tilt 0.0154-0.0172 rad
  // against the cascade's 0.0100, RMS 0.0006 m); here the tilt is the
  // cascade's and the RMS still 3x below it (docs/mpc.md). Velocity 3e3 with
  // position 3e3 was overdamped (a 0.5 m step 0.47 m after 3 s); 90 lost
  // aggressive's tracking (RMS 0.0078 m). Raising the tilt weight instead
  // (200, pitch rate 10) destabilised the hover (0.52 rad) and made
  // DENSE-AUL late.
  double position_weight_1_m2 = 3e3;
  double velocity_weight_s2_m2 = 1000.0;
  double tilt_weight_1_rad2 = 20.0;
  double pitch_rate_weight_s2_rad2 = 1.0;
  // The altitude (z) position weight is this many times the x one, in every
  // weight set and the terminal weight [1]. At the tilt limit the vehicle
  // cannot follow both axes, and the plan traded them equally: on the fastest
  // trajectory SETPOINT accepts (quintic (1, 1) m in 0.76 s, 10 m/s^2 per
  // axis; case aggressive_limit) it gave up 0.48 m of altitude against the
  // cascade's 0.23. At 10 it gives up 0.17 m and x lags instead; the other
  // cases fly as before or better (docs/mpc.md, "At the limits").
  double altitude_weight_factor = 10.0;
  // The same weights in the hover-infeasible descent (MpcPlanInput::
  // level_descent, a 70 % loss): its sink-rate reference cannot be flown,
  // and with position dominant the plan bought vertical impulse with the
  // strong rotor pulsed 0 <-> omega_max, the pitch swinging at +-2.5 rad/s
  // into the flare (touchdown 0.97 m/s [0.87, 1.11], 4 of 10 seeds over 1).
  // Position 10x lower, tilt 25x and pitch rate 50x higher: level and calm
  // (|pitch rate| ~0.2 rad/s before the flare), touchdown 0.93 [0.87, 0.98].
  // Tilt 1000 / rate 100 or position 100-1000 land alike (max 0.98); velocity
  // 3000 made the solves late (p99 2.9 ms); position 3-30 sank faster (max
  // 1.03-1.10). Tilt 5000 (was 500): a 70-80 % loss mid-climb (cases
  // agg_loss*) touched down at 0.33-0.35 rad with 500, at most 0.295 with
  // 5000 (5 seeds), the hover loss_70 unchanged. Docs/mpc.md.
  // The tilt and pitch rate weights of a fully-actuated vehicle (N >= 3
  // rotors whose allocation spans F_x, F_z and the torque; the N-input MPC of
  // controller/multi_arm_mpc.h): its tilt reference is 0 and it moves
  // sideways through F_x, so tilting is a cost, not a means. With the
  // birotor's 20 / 1 the trirotor (config/vehicles/trirotor.yaml) bought F_x
  // with tilt (0.39 rad on a 1 m lateral step); 1e5 / 5000 flies it at 0.0036
  // rad and settles as fast (1.93 s into 5 cm). Keep the tilt weight within
  // ~20x the pitch rate weight: 1e5 / 1000 and 2e5 / 1000 drifted 0.07-0.14 m
  // in altitude (the unmodelled arm modes under a stiff, undamped attitude;
  // docs/mpc.md "N inputs"). The birotor's MPC never reads these.
  double level_tilt_weight_1_rad2 = 1e5;
  double level_pitch_rate_weight_s2_rad2 = 5000.0;
  // The tilt and pitch rate weights of a fully-actuated vehicle planning
  // about a tilted hover (the trirotor with a weak rotor 2 or 3,
  // docs/controller.md "A tilted hover without a spare rotor"; the
  // quadrotor with a dead rotor, "Spare rotors"): the weak rotor near its
  // bound makes F_x one way only, so the plan tilts about the hover to
  // move, as the birotor does. With the level
  // weights the trirotor with rotor 2 at 12 % drifted 0.37 m sideways after
  // the loss (RMS 0.150 m, median of seeds 1-5); 500 / 50: 0.023 m, peak
  // tilt 0.36 rad; the birotor's 20 / 1: 0.015 m but 0.51 rad.
  double tilted_hover_tilt_weight_1_rad2 = 500.0;
  double tilted_hover_pitch_rate_weight_s2_rad2 = 50.0;
  // The birotor MPC's pitch rate weight while the reference is steady (its
  // acceleration below steady_max_accel_m_s2 [m/s^2]: a hover, a slow move
  // such as gentle's), in place of pitch_rate_weight_s2_rad2 (the recovery
  // and descent weights before it). What tilts the hover is the turbulence's
  // torque, and 1 let the plan buy millimetres of position with it: peak
  // tilt 1.27-1.34x the cascade's (hover, gentle with the motor +70 %,
  // 10 seeds); 10 brings it to 0.87-1.00x at RMS 0.0007 m (0.0006 with 1).
  // Not while the reference accelerates: 10 there lagged the aggressive
  // manoeuvre (RMS 0.0080 against 0.0045 m; docs/mpc.md "Steady weights").
  // The N-input MPC does not take them: it has no recovery weights, and on
  // the two-arm description a 40 % loss then cost 0.0029 m of altitude
  // instead of 0.0024 (5 seeds).
  double steady_pitch_rate_weight_s2_rad2 = 10.0;
  double steady_max_accel_m_s2 = 0.05;
  double descent_position_weight_1_m2 = 300.0;
  double descent_velocity_weight_s2_m2 = 1000.0;
  double descent_tilt_weight_1_rad2 = 5000.0;
  double descent_pitch_rate_weight_s2_rad2 = 50.0;
  // The same weights for recovery_s after a sudden pitch disturbance (a
  // rotor losing thrust: disturbance_pitch_step_rad_s2 below): attitude
  // first, the altitude it costs is won back after. With the tracking weights
  // the plan lowered the strong rotor only as fast as the altitude allowed
  // (60 % loss: 0.046 rad peak tilt); tilt 500 / rate 50 (the descent's)
  // stop the rotation in ~60 ms (docs/mpc.md, rotor faults).
  double recovery_position_weight_1_m2 = 3e3;
  double recovery_velocity_weight_s2_m2 = 1000.0;
  double recovery_tilt_weight_1_rad2 = 500.0;
  double recovery_pitch_rate_weight_s2_rad2 = 50.0;
  double recovery_s = 0.5;  // how long the recovery weights hold after the step [s]
  // Input weights [1/(rad/s)^2]: on the distance from the feed-forward speed
  // (the speed that holds the reference acceleration with the rotor's
  // efficiency), and on the step-to-step change (smoothness, below the arm
  // modes). Small: the constraints, not these, bound the commands.
  double input_weight_s2_rad2 = 1e-6;
  double input_rate_weight_s2_rad2 = 1e-6;

  // Command rate limit [rad/s^2]: 30000 rad/s^2 takes a rotor from hover
  // (699 rad/s) to omega_max in 17 ms, half the motor time constant, so it
  // hardly slows the response but rules out the bang-bang steps that ring
  // the 65/80 Hz arm modes.
  double max_omega_rate_rad_s2 = 30000.0;
  // Tilt limit [rad], soft: a slack variable with the weight below (a hard
  // limit is infeasible whenever the vehicle is already past it, e.g. at a
  // rotor fault). Same value as the cascade's max_tilt_rad.
  double max_tilt_rad = 0.5;
  double tilt_slack_weight = 1e8;  // per rad^2 of excess, far above the tracking terms [1/rad^2]

  // Offset-free tracking: the one-step prediction error of the model is
  // low-passed into a constant acceleration disturbance (x, z, pitch) that
  // the prediction carries. 0.3 s: slower than the pitch loop, faster than
  // the cascade's integrator (Ki/Kp = 1/3 s).
  double disturbance_time_constant_s = 0.3;
  double max_disturbance_m_s2 = 5.0;     // clamp of the x, z disturbance [m/s^2]
  double max_disturbance_rad_s2 = 50.0;  // clamp of the pitch disturbance [rad/s^2]
  // A pitch prediction error larger than this is taken into the disturbance
  // at once, not low-passed, and starts recovery_s of the recovery weights
  // [rad/s^2] (0: never). A rotor losing 40 % shows here as ~30 rad/s^2 one
  // solve before FORCE's efficiency does; in flights without a fault the
  // error stays below 8 rad/s^2 (docs/mpc.md).
  double disturbance_pitch_step_rad_s2 = 15.0;

  // Real time: a solve longer than this falls back to the cascade for the
  // period [s]. Half the period leaves the other half for the rest of it.
  double deadline_s = 0.005;
  // What the deadline is measured in. The lock-step loop, whose virtual clock
  // does not run during a solve, always uses kWork: on CPU time a shared
  // machine decided which solves were late, and the same seed did not fly the
  // same twice. The solve-time statistics are on the wall clock, or on CPU
  // time for kThreadCpu and kWork.
  MpcDeadlineClock deadline_clock = MpcDeadlineClock::kWall;
  // kWork: the most solver work (alglib's iterations, else Cholesky
  // factorizations, else matrix-vector products; MpcQpSolution::iterations) a
  // solve may take and count as on time [1]. 200 is BLEIC's iteration cap;
  // DENSE-AUL's factorizations are bounded by its 10 outer iterations
  // (measured 2-7 on aggressive and loss_60, p50 2; docs/mpc.md "Deadline"),
  // so its lock-step solves are never late for want of time.
  int deadline_work = 200;
  // DENSE-IPM: its cost is bounded where the others' is not. DENSE-AUL
  // (warm-started) is the cheapest in ordinary flight (CPU per solve p50/p99
  // 170/330 us against DENSE-IPM's 340/650 us and BLEIC's 420/850 us,
  // aggressive), but with the soft tilt limit active (case aggressive_limit)
  // its inner iterations reached 200-310 Cholesky factorizations and
  // 5.5-9.7 ms per solve, over the 5 ms deadline (p99 7.3 ms, 25 fallbacks in
  // one flight); DENSE-IPM solved the same flight at p99 470 us without a
  // fallback (docs/mpc.md, "At the limits").
  MpcQpAlgorithm algorithm = MpcQpAlgorithm::kDenseIpm;
  double solver_tolerance = 1e-6;  // alglib stopping tolerance (scaled) [1]
  int max_iterations = 200;        // BLEIC's iteration cap (the answer at the cap is still checked)

  // True: the prediction uses FORCE's thrust_scale per rotor (a weak rotor is
  // planned for); false: the nominal map (thrust_scale 1).
  bool use_thrust_scale = true;
};

}  // namespace birotor
