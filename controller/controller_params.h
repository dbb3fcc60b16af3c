// Parameters of the flight controllers as plain structs with documented
// defaults: the gains of the cascaded position/pitch law (shared by the
// simulator's autopilot and birotor-controller) and the options of the
// controller service (state observer, force feedback, fallback, descent).
// params/controller_config_yaml.h loads them.
#pragma once

#include <cstdint>

#include "controller/mpc_params.h"
#include "model/vehicle_description.h"

namespace birotor {

// Cascaded PD (+ integral) on the rigid-body approximation, 500 Hz. Outer
// loop: desired acceleration from the position error (critically damped,
// 3 rad/s); inner loop: desired pitch acceleration from the tilt error
// (20 rad/s, below the motor lag and far below the 65/80 Hz arm modes).
struct ControllerParams {
  double rate_hz = 500.0;
  double position_kp_1_s2 = 9.0;
  double position_kd_1_s = 6.0;
  double position_ki_1_s3 = 3.0;
  double attitude_kp_1_s2 = 400.0;
  double attitude_kd_1_s = 32.0;
  double attitude_ki_1_s3 = 600.0;
  double max_tilt_rad = 0.5;
  double max_integral_m_s2 = 3.0;              // clamp of the position integral term
  double max_attitude_integral_rad_s2 = 40.0;  // clamp of the attitude integral term
};

// Body-state observer of the controller service (it never sees TRUTH):
// position and velocity per world axis propagated with the accelerometer and
// corrected by POSE with the gains of a critically damped second-order
// observer, L = [2 w, w^2]; tilt propagated with the gyro and pulled towards
// POSE's phi with the crossover frequency below.
struct ObserverParams {
  double position_bandwidth_rad_s = 10.0;  // w of the position/velocity observer [rad/s]
  double attitude_crossover_rad_s = 5.0;   // gyro/POSE complementary-filter crossover [rad/s]
};

// What the controller service does with its inputs, and when it stops
// trusting one (issue 23: its own clock, one publisher per input, plausible
// values only, a POSE gate).
struct SupervisionParams {
  double pose_timeout_s = 0.05;    // POSE older than this: controlled descent [s]
  double imu_timeout_s = 0.01;     // IMU older than this: propagate without it [s]
  double force_timeout_s = 0.005;  // FORCE older than this: fall back towards the nominal map [s]
  double force_recovery_s = 0.05;  // FORCE healthy and on time this long before force feedback resumes [s]
  double descent_rate_m_s = 0.3;   // sink rate of the controlled descent [m/s]
  // Input stamps against the controller's own clock: later than now + future
  // or earlier than now - past are refused and counted; they never move the
  // clock. An input whose newest stamp is ahead of the clock (negative age)
  // is stale.
  double clock_future_window_s = 0.01;  // [s]
  double clock_past_window_s = 0.2;     // [s]
  // The clock is set (and relatched) only when two different inputs (of
  // POSE, IMU, FORCE) agree on the vehicle time, stamp - host time, within
  // this: a lone stream stamped ahead never sets it (issue 37) [s].
  double clock_agreement_s = 0.02;
  // One publisher per input (controller/seq_stream_lock.h, issue 37): FORCE
  // and POSE locked to the first seq stream; a message belongs to it when,
  // after receiver time dt since the stream's last message, its seq step is
  // within 1 + max_rate dt (1 + stream_rate_margin) + stream_seq_slack and
  // its stamp advance within dt + stream_stamp_slack_s. Any other message
  // while the locked stream is alive is a conflict (STATUS_INPUT_CONFLICT):
  // BOTH streams are refused (rejected_foreign) until one of them has been
  // silent for conflict_hold_s; force feedback is dropped, and POSE refused
  // longer than pose_timeout_s gives the controlled descent.
  double pose_stream_max_rate_hz = 150.0;    // POSE: 100 Hz nominal [Hz]
  double force_stream_max_rate_hz = 1500.0;  // FORCE: 1 kHz nominal [Hz]
  double stream_rate_margin = 0.5;           // [1]
  double stream_seq_slack = 3.0;             // seq steps beyond the rate (a burst after a stall) [1]
  double stream_stamp_slack_s = 0.05;        // stamp ahead of the receiver's time (latency jitter) [s]
  double stream_silence_s = 0.2;             // a silent stream is given up (a restarted publisher) [s]
  double conflict_hold_s = 0.3;              // [s]
  // FORCE thrust_scale outside this band is refused (not clamped): no
  // healthy or faulty rotor of this vehicle is outside it [1].
  double min_plausible_thrust_scale = 0.2;
  double max_plausible_thrust_scale = 2.0;
  // Except at the floor: a VALID FORCE flagging rotor i's fault with its
  // scale below min_plausible_thrust_scale this many samples in a row is
  // flown at the floor (the scale is at most that; an 80 % loss), not
  // refused. A single ringing sample (mu 0.08 right after a 70 % loss) and
  // a scale without the fault flag are still refused [samples].
  int32_t at_floor_samples = 5;
  // POSE innovation gate against the controller's own observer: a sample
  // farther than this is refused; when every sample has been refused for
  // pose_gate_reset_s the observer is re-initialised on POSE (the vehicle
  // really is there).
  double pose_gate_position_m = 0.3;  // [m]
  double pose_gate_angle_rad = 0.3;   // [rad]
  double pose_gate_reset_s = 0.2;     // [s]
  // Re-acquisition through the gate: pose_reacquire_count gated POSEs in a
  // row, each within pose_reacquire_position_m / _angle_rad of where the
  // previous one and the observer's (IMU-propagated) velocity and pitch rate
  // put it, are the vehicle however far the observer has drifted: the
  // observer is moved onto the newest (velocity and rate kept).
  int32_t pose_reacquire_count = 5;         // [1]
  double pose_reacquire_position_m = 0.02;  // [m]
  double pose_reacquire_angle_rad = 0.03;   // [rad]
  // Every controlled descent (POSE lost, hover infeasible) flies level: the
  // law's tilt target within degraded_max_tilt_rad (0 while levelling), and
  // each rotor command moves by at most degraded_omega_rate_rad_s2 x the
  // period (no bang-bang between 0 and omega_max).
  double degraded_max_tilt_rad = 0.1;           // [rad]
  double degraded_omega_rate_rad_s2 = 20000.0;  // [rad/s^2]
};

// How FORCE's thrust_scale becomes the efficiency the rotor map uses
// (controller/efficiency_conditioner.h, issue 25): followed only while FORCE
// flags a rotor fault or a thrust deficit, relative to the unflagged flight
// before, filtered and rate limited, frozen until airborne, decaying towards
// 1 otherwise; times the trusted absolute mu0 (issue 36 item 5).
struct EfficiencyParams {
  double airborne_force_fraction = 0.8;  // airborne: FORCE's total thrust above this share of the weight [1]
  double airborne_s = 0.05;              // ... for this long [s]
  double baseline_tau_s = 1.0;           // low-pass of the unflagged thrust_scale (the reference) [s]
  double change_threshold = 0.1;         // |mu / mu0 - 1| above this is a real change too [1]
  double fault_tau_s = 0.01;             // first order towards mu / mu0 while flagged [s]
  double max_rate_1_s = 50.0;            // rate limit of the efficiency [1/s]
  double max_relative_sigma = 1.0;       // force_std / max(|force|, weight / N) above: not followed [1]
  double blend_after_s = 0.2;            // a fallback at least this long is blended out of [s]
  double blend_s = 1.5;                  // back from a fallback: blended in (time constant blend_s / 3) [s]
  double decay_s = 3.0;                  // unflagged or FORCE unusable: towards 1 with this time constant [s]
  // The change factor c_i followed is at most this: no fault makes a rotor
  // stronger, and a healthy rotor reads high only for moments beside
  // another's loss; a motor lag the file lacks swings mu_i to 2 and more
  // (EfficiencyConditioner) [1].
  double max_change_gain = 1.2;
  // FORCE not VALID by MODEL_MISMATCH alone: a rotor it flags is still
  // flown at its change relative to the unflagged rotors (false: the
  // nominal map until VALID).
  bool mismatch_relative = true;
  // ... once the fault flag has held this long with the relative change
  // beyond mismatch_min_change throughout (a mismatch's own errors flag the
  // rotors by turns, up to some 15 % apart; a 25 % loss reads 20-30 % under
  // a mismatch) [s], [1].
  double mismatch_confirm_s = 0.03;
  double mismatch_min_change = 0.2;
  // ... and within this of itself over that run; once flown, wandering this
  // far from the confirmed change ends the rule until VALID again [1].
  double mismatch_max_spread = 0.1;
  // A confirmed change is flown with a time constant of this many times the
  // time its fault was held (the nominal loop's integrators took it on
  // meanwhile) [1].
  double mismatch_handover_factor = 2.0;
  // The absolute rule (issue 36 item 5): a trusted mu0_i is flown itself,
  // e_i = a_i c_i with a_i towards mu0_i (EfficiencyConditioner).
  double absolute_tau_s = 0.2;                // time constant of a_i towards mu0_i (0: off) [s]
  double absolute_settle_s = 0.02;            // airborne FORCE seen before mu0 is trusted [s]
  double absolute_max_relative_sigma = 0.05;  // trusted only while force_std_i / |force_i| is below [1]
  double absolute_threshold = 0.05;           // |mu0_i - 1| above: flown; back below half of it: a_i towards 1 [1]
  double absolute_min_sigmas = 4.0;           // ... and above this many of mu0_i's relative sigma (0: off) [1]
  double min_absolute_efficiency = 0.7;       // bounds of a_i [1]
  double max_absolute_efficiency = 1.3;       // [1]
  double feasibility_margin = 1.02;           // hover needs 2 min_i(e_i c_T omega_max^2) >= margin x weight [1]
  double infeasible_s = 0.1;                  // infeasible this long: level controlled descent [s]
  // Spare rotors (more rotors than controlled axes, e.g. the quadrotor;
  // controller/hover_space.h): when the least-norm hover thrusts leave
  // [spare_min_share, spare_max_share] x e_i c_T,i omega_max^2 on some rotor,
  // the allocation starts from the nearest hover within those shares
  // (within [spare_min_share, 1 / feasibility_margin] when there is none),
  // and hover is feasible while a hover within [spare_min_share, 1 /
  // feasibility_margin] exists (every rotor kept off 0 for control both ways).
  double spare_min_share = 0.05;  // [1]
  double spare_max_share = 0.8;   // [1]
  // With no level hover within those shares, a fully actuated vehicle with
  // spare rotors may hover tilted up to this (the body balances the lateral
  // force a rotor that makes nothing leaves; HoverSpace::
  // NearestTiltedWithinShares), and one without a spare rotor (the
  // trirotor, once no level hover is within [0, 1 / margin]): the cascade
  // with every rotor within [spare_min_share, spare_max_share] (room for its
  // torque above the weak rotor), mode mpc up to 1 / margin; 0: level
  // hovers only. 0.45: the trirotor holds a dead rotor 2 or 3 at 0 N
  // 0.40 rad off level (MultiArmLaw's pinned hover).
  double spare_hover_tilt_rad = 0.45;  // [rad]
  // The cascade's tilted hover keeps every rotor at least this share (when
  // one within spare_hover_tilt_rad does, else spare_min_share): the rotor
  // whose lateral thrust the tilt balances is the only one that can give
  // F_x back, so it needs room below [1].
  double spare_tilted_min_share = 0.1;  // [1]
  // With spare rotors a rotor FORCE flags below min_plausible_thrust_scale
  // (at_floor_samples reports in a row) is flown at what those reports
  // average instead of at the floor; once they average below this the
  // cascade flies it as making nothing (retired: not driven; a dead rotor
  // reads about 0) until that run of reports ends, the MPC at this value
  // (its model needs e > 0); 0: never retired [1].
  double spare_retire_scale = 0.05;  // [1]
  // Infeasibility from the vehicle itself (force feedback; FORCE refused at
  // its plausibility floor on a large loss): the allocation limited for
  // sink_detect_s while the vehicle is more than sink_detect_altitude_m below
  // its reference and falling behind it, the sink growing over that window.
  // The weak rotor's efficiency is then at most what FORCE last said
  // (refused below the floor included) and at most the feasibility bound
  // margin x weight / (2 c_T omega_max^2).
  double sink_detect_altitude_m = 0.15;  // [m]
  double sink_detect_s = 0.1;            // [s]
  // A sink is a judgement made in a loss's transient on a weight model that
  // may be wrong (a payload); the rotors' own measure may undo it
  // (Cause::kSink only): level and calm, sinking faster than
  // recover_min_sink_m_s by the observer and by the height (a vehicle on the
  // ground does not move, though the observer's climb rate decays for a
  // while after the impact), over each of two sink_recover_s windows in a
  // row (an impact fills at most one) the mean commands and the vertical
  // acceleration a_z say every rotor holds its share of the weight with the
  // margin, (g + a_z) / (g max_i mean (omega_i / omega_max)^2) >=
  // feasibility_margin: hover is feasible again (payload +15 %, rotor 1 at
  // 0.3 then back to 0.45: the vehicle holds with 12 %). The sink detection
  // re-arms once the vehicle no longer falls behind its reference. 0:
  // latched for the flight.
  double sink_recover_s = 0.15;       // [s]
  double recover_min_sink_m_s = 0.1;  // [m/s]
  // The infeasible descent first levels: tilt target 0 until |tilt| below
  // level_tilt_rad and |pitch rate| below level_rate_rad_s, then descends.
  double level_tilt_rad = 0.05;   // [rad]
  double level_rate_rad_s = 0.5;  // [rad/s]
  // The flare of that descent (FlareForcesFor, controller/rotor_allocation.h):
  // sinking faster than descent_rate_m_s and lower than the sink covers in
  // flare_time_s above the ground (the first POSE: the take-off level), the
  // strong rotor may exceed the weak one so that |tilt| reaches flare_tilt_rad
  // at touchdown, trading tilt and pitch rate for touchdown speed (0: no flare).
  double flare_tilt_rad = 0.08;  // tilt budget at touchdown [rad]
  // The same budget on a fully actuated vehicle (MultiArmControlMode
  // kFullyActuated: the trirotor, the quadrotor): its canted rotors' thrust
  // turns towards the vertical as the body tilts, so the tilt buys more
  // there (trirotor, rotor 1 at 30 %: touchdown 2.26 m/s at 0.08 rad, 2.12 at
  // 0.2, the nominal map's 2.20; docs/controller.md, "Flare with N rotors").
  double flare_tilt_fully_actuated_rad = 0.2;  // [rad]
  double flare_time_s = 0.1;                   // flare height = sink rate x this [s]
  // Motor-lag lead on a falling efficiency: omega_cmd = omega + lead_s d(omega)/dt
  // with d(omega)/dt = -omega / (2 e) de/dt (de/dt < 0 only), the inverse of the
  // first-order motor lag (tau_m, model/plant.h) for the efficiency's share of the
  // command only (0: off) [s].
  double motor_lead_s = 0.035;
  // Motor-lag lead on the cascade's thrust: omega_cmd = omega (lead_s s + 1)
  // / (filter_s s + 1) for the change of the allocated thrust at this
  // period's e (the inverse of the first-order motor lag, tau_m of the file,
  // down to a lag of filter_s; 0: off; filter_s >= lead_s: off). Without it
  // the cascade's attitude loop lost the vehicle in hover once the rotor
  // lagged 1.9x the file's tau_m; with it, it holds to 3.5x. The filter bounds
  // the noise the lead amplifies to lead_s / filter_s (hover: the largest
  // command change per period 4 rad/s without the lead, 81 unfiltered, 20) [s].
  double thrust_lead_s = 0.035;
  double thrust_lead_filter_s = 0.005;
};

// What the controller accepts on SETPOINT (controller/setpoint_input.h).
struct SetpointParams {
  double timeout_s = 0.5;                     // newest setpoint held this long, then hover where the vehicle is [s]
  double max_extrapolation_s = 0.05;          // a held setpoint moves on with its feed-forward this long [s]
  double future_window_s = 0.1;               // stamps later than the controller's clock plus this are refused [s]
  double min_interval_s = 0.002;              // rate limit: stamps closer than this to the newest are refused [s]
  double max_abs_position_m = 100.0;          // |x|, |z| accepted [m]
  double max_feed_forward_speed_m_s = 5.0;    // |velocity feed-forward| accepted, per axis [m/s]
  double max_feed_forward_accel_m_s2 = 10.0;  // |acceleration feed-forward| accepted, per axis [m/s^2]
  // The reference flown moves per axis at most this fast [m/s] and with at
  // most this acceleration [m/s^2]: 1.5x the fastest legitimate references,
  // aggressive ((1, 1) m in 2 s: 1.875 / 2 = 0.94 m/s per axis) and the
  // figure-8 of the identification flights (0.5 m legs in 1.3 s: 5.77 x 0.5
  // / 1.3^2 = 1.71 m/s^2). 2.6 m/s^2 needs atan(2.6 / 9.81) = 0.26 rad of
  // tilt, inside max_tilt_rad 0.5. (mass_id's 0.4 m in 0.8 s, 3.61 m/s^2,
  // if flown through birotor-controller, is shaped.)
  double max_speed_m_s = 1.4;
  double max_accel_m_s2 = 2.6;
  double max_jump_m = 0.5;  // distance from the reference flown now accepted [m]
  // Reference shaping: a target step this much beyond max_speed dt (and a
  // velocity step this much beyond max_accel dt) is still followed exactly.
  double shaping_position_tolerance_m = 0.001;   // [m]
  double shaping_velocity_tolerance_m_s = 0.01;  // [m/s]
  // Natural frequency of the (critically damped) shaping reference model
  // [rad/s]; <= 4 max_accel / max_speed (7.4) so it brakes in time.
  double shaping_bandwidth_rad_s = 4.0;
  // The first control period flies the setpoint exactly when it is this
  // close to the start position (the first POSE and its noise) [m].
  double start_snap_m = 0.02;
  // Feed-forward consistency with the previous accepted setpoint, dt apart:
  // |(v0 + v1)/2 dt - dp| <= tol_v max(dt, floor), and with both velocities
  // given |(a0 + a1)/2 dt - dv| <= tol_a max(dt, floor) (a0 left out when
  // not given); an acceleration without its velocity is refused.
  double ff_velocity_tolerance_m_s = 0.2;  // [m/s]
  double ff_accel_tolerance_m_s2 = 1.0;    // [m/s^2]
  double ff_interval_floor_s = 0.01;       // [s]
  // Publisher lock: one publisher's seq moves by 1 .. 1 + lock_max_rate_hz
  // dt (1 + lock_rate_margin) + lock_seq_slack and its stamp by at most
  // dt + lock_stamp_slack_s in an arrival interval dt.
  double lock_max_rate_hz = 500.0;  // [Hz]
  double lock_rate_margin = 0.5;
  double lock_seq_slack = 2.0;       // [messages]
  double lock_stamp_slack_s = 0.02;  // [s]
  // A second publisher while the locked one is alive: both refused until
  // one has been silent this long [s].
  double conflict_hold_s = 1.0;
};

// Everything birotor-controller (and the lock-step closed loop) needs.
struct ControllerConfig {
  // The controller's vehicle; a birotor (its laws run on BirotorModelOf).
  VehicleDescription vehicle = BirotorDescription(BirotorParams());
  bool force_feedback = true;  // mode: force_feedback (true) or nominal (false)
  // mode: mpc: the model predictive controller (controller/mpc_controller.h)
  // flies, the cascade (on force feedback) is its per-period fallback.
  bool model_predictive = false;
  MpcParams mpc;  // the mpc: section
  ControllerParams gains;
  ObserverParams observer;
  SupervisionParams supervision;
  EfficiencyParams efficiency;
  SetpointParams setpoint;
};

// MOTOR_COMMAND rate [Hz]: the cascade's rate_hz, or in mode mpc the MPC's.
inline double CommandRateHz(const ControllerConfig& config) {
  return config.model_predictive ? config.mpc.rate_hz : config.gains.rate_hz;
}

}  // namespace birotor
