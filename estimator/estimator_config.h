// Options of the force estimator (method, filter tuning, gates, timeouts),
// with the reference vehicle; every field has a documented default and is
// loaded from the `estimator:` section of a parameter file by params/.
#pragma once

#include <string>
#include <vector>

#include "estimator/model_consistency_options.h"
#include "model/vehicle_description.h"

namespace birotor {

// Tuning of the extended Kalman filter (estimator/ekf_force_estimator.h).
// Spectral densities q are continuous-time: the variance added over dt is q dt.
struct EkfOptions {
  // Measurement noise (one sigma).
  double strain_noise_rad = 2e-5;        // strain-gauge deflection noise [rad]
  double motor_speed_noise_rad_s = 5.0;  // ESC telemetry noise [rad/s]
  double gyro_noise_rad_s = 0.005;       // IMU pitch-rate noise [rad/s]
  // The strain noise learned online (estimator/noise_adaptation.h,
  // docs/estimator.md): each gauge's variance strain_noise_rad^2 times a
  // scale in [strain_noise_scale_min, strain_noise_scale_max] matched to the
  // sample-to-sample scatter of its innovations over a fading memory of
  // strain_noise_window_s, used once strain_noise_min_samples samples were
  // learned from, frozen for strain_noise_hold_s after a gated sample or a
  // rotor fault. The default bounds never go below the file's noise and at
  // most 2.5x its sigma (6.25x its variance): the issue-36 gauges at twice the
  // file's sigma need 4x.
  bool adapt_strain_noise = true;
  double strain_noise_window_s = 2.0;    // [s]
  double strain_noise_scale_min = 1.0;   // on the variance [1]
  double strain_noise_scale_max = 6.25;  // on the variance [1]
  int strain_noise_min_samples = 200;    // strain samples learned from before the scale moves
  double strain_noise_hold_s = 0.2;      // [s]
  // The accelerometer's noise learned the same way (NoiseAdaptation, with
  // AccelerometerNoiseSettings): accel_noise_m_s2^2 times a scale in [1,
  // accel_noise_scale_max] matched to the a_z innovations' sample-to-sample
  // variance over accel_noise_window_s, used once accel_noise_min_samples
  // pairs were learned from, frozen for accel_noise_hold_s after a thrust
  // step (the strain gated) or a rotor fault. Gated samples count too (a
  // 20x noisier accelerometer is gated on most samples until learned), each
  // capped at accel_noise_clip times the current estimate, so a spike moves
  // it little. Until accel_noise_trust_samples pairs, the birotor's EKF fuses
  // a_z with the scale's upper bound at accel_noise_trust_sigmas
  // (CautiousScale; the N-arm EKF the scale as it stands, which starts at
  // the median of its first pairs: MultiArmAccelerometerNoiseSettings).
  // docs/estimator.md "Measurement noise learned online".
  bool adapt_accel_noise = true;
  double accel_noise_window_s = 2.0;      // [s]
  double accel_noise_scale_max = 1000.0;  // on the variance [1] (sigma up to 31.6x the file's)
  int accel_noise_min_samples = 5;     // accelerometer sample pairs learned from before the scale moves (and the N-arm
                                       // EKF, at an airborne start, fuses it)
  double accel_noise_hold_s = 0.2;     // [s]
  double accel_noise_clip = 9.0;       // one pair's variance sample at most this x the estimate [1]
  int accel_noise_trust_samples = 50;  // pairs before the scale is fused as learned (its upper bound until then)
  double accel_noise_trust_sigmas = 1.0;  // that bound: scale (1 + sigmas sqrt(2 / n)) after n pairs [1]
  bool use_motor_telemetry = true;        // fuse omega_meas when finite
  bool use_gyro = true;                   // fuse IMU gyro_y when IMU samples arrive
  // Accelerometer a_z in free flight (the total thrust, independent of the
  // gauges: what makes the gauge offsets observable in the air). Its noise
  // is the white noise of the reference sensor; a real vehicle's IMU also
  // sees frame vibration: raise this to the a_z scatter measured in hover.
  bool use_accelerometer = true;
  double accel_noise_m_s2 = 0.05;  // [m/s^2]
  // Gauge offsets e_i as filter states (random walks): their prior sigma is
  // the vehicle's gauge_offset_std_rad (or the tare's, or the state file's)
  // and their driving noise its gauge_drift_psd_rad2_s, both divided by the
  // gauge scale. false: the offsets stay at the calibration, exactly known.
  bool estimate_gauge_offsets = true;
  // N-arm EKF on a vehicle with more rotors than the rigid body pins (N > 3,
  // the wrench's null space): the offset combinations that mirror a force
  // there (estimator/multi_arm_offset_hold.h) are not moved by the
  // measurements in flight (a Schmidt hold: their prior, drift and
  // correlations stay in P and in the force sigma); on the ground they are
  // learned as the others. false: every combination updated (in hover the
  // estimate wanders along them: docs/estimator.md). No effect for N <= 3.
  bool hold_unseen_offsets = true;
  // Slow vehicle parameters learned in flight (issue 27, docs/mismatch.md),
  // each a random walk starting at the parameter file's value (1) with the
  // prior sigma below (the reference file carries no sigma for k, s_i or m:
  // these are the widths of an unidentified vehicle). Only the combinations
  // the flight determines are states: per arm the strain scale g_i (gauge
  // scale over stiffness: z_i = g_i b_i + e_i) and the body mass m. g_i and m
  // scale the same force (strain vs accelerometer), so they are told apart
  // only by manoeuvres (the gyro weighs f1 - f2 through the known inertia);
  // their joint covariance keeps the force sigma honest meanwhile.
  bool learn_strain_scale = false;
  double strain_scale_prior_std = 0.1;  // [1]
  double strain_scale_psd_1_s = 1e-7;   // [1/s]
  // The body mass (a payload) as one of two hypotheses (docs/mismatch.md
  // "Learning the payload"): the file's mass, or a payload with the prior
  // sigma below; the published forces and mass are averaged over both with
  // the posterior probability of a payload (estimator/parameter_hypotheses.h),
  // which starts at body_mass_change_probability. Live in free flight from
  // the lift-off on (no slow_learning_delay_s). Off by default: on, the
  // payloads are learned honestly (body +10 % airborne: MAE 0.127 N, 2-sigma
  // share 0.995, was 1.96 N and 0.000; from the ground 0.077 N, 0.979, with
  // step_hold_s) but the stiffness / gauge-scale / all-at-once mismatches
  // are explained by a wrong mass with a confident sigma (birotor-eval
  // --mismatch-targets --seeds 5 --params F, F with it on).
  bool learn_body_mass = false;
  // 0.15: a payload of 15 % of the body is one sigma (issue 36's documented
  // default for masses; was 0.1) [1].
  double body_mass_scale_prior_std = 0.15;  // relative to the file's body mass [1]
  double body_mass_scale_psd_1_s = 1e-7;    // [1/s]
  // P(H1) before any data: the prior probability that the body mass is not
  // the file's, in (0, 1] [1]. 0.1: the matching hover and gentle flights
  // keep their MAE (0.068 N) with a 2-sigma share of 0.974 / 0.976 (0.959
  // with the mass fixed); larger values widen it towards 0.98.
  double body_mass_change_probability = 0.1;
  // They are learned only in free flight (airborne, f1 + f2 above half the
  // weight), after a lift-off only once it lasted this long (a filter that
  // starts in the air learns at once): the lift-off transient (the ground contact's
  // 0.02 s filter, the arms ringing down) learned at once split gauge_drift's
  // scales by 3.6 % (MAE 0.49 N and a MODEL_MISMATCH). Also the settling
  // after a start or a lift-off at whose end the strain scales and the gauge
  // offsets are split again (SplitScaleAndOffsetAgain, issue 27) [s].
  double slow_learning_delay_s = 0.5;
  // During that settling (learned strain scales and gauge offsets) VALID is
  // withheld once a gauge offset moved more than this many of its sigmas
  // (at the settling's start) from its value then: the part of the readings
  // the file's model does not explain sits in the offsets then, and a
  // payload's forces are off before anything can say so. 2: body +10 %
  // airborne keeps every 2 s window of VALID estimates honest on seeds
  // 1-10 (3: seed 8 still had a window at share 0.000) while a matching vehicle is
  // VALID from its first estimates (force feedback on c_T -15 %: 0.048 m
  // sag instead of 0.127 m with the whole settling withheld); 0: the whole
  // settling withheld [sigma].
  double settling_offset_limit_sigma = 2.0;
  // While a slow parameter learns, through a thrust step and a lift-off the
  // learned parameters (strain scales, body mass) and the gauge offsets are
  // held: Schmidt consider states, no gain, their correlations kept
  // (estimator/kalman_fusion.h, KalmanUpdate), while the strain gate rejects
  // samples and for this long after it let a step in (the thrust scales
  // inflated) or after a lift-off. Without it the filter's forces ring for
  // ~15 ms after a step (uncertain by ~2 N) and the accelerometer reads the
  // ringing as a payload (thrust_loss seed 3: the mass stepped 4.00 -> 4.15
  // kg within 10 ms and stayed, MAE 0.43 N), and at a lift-off the contact,
  // judged on the file's mass, lets go before a heavier vehicle does (body
  // +10 %, ground start: MAE 0.34 N). 0.2 s: 0.15-0.25 s give the same
  // figures; 0.5 s raised MODEL_MISMATCH after a 40 % loss in the closed
  // loop (docs/mismatch.md, "Holding through a step and a lift-off").
  // Without slow parameters nothing is held [s].
  double step_hold_s = 0.2;
  // Process noise. Thrust scale mu: random walk standing in for the
  // Gauss-Markov turbulence. Its driving noise 2 sigma^2 / tau (2e-3 /s for
  // the reference) made the filter pessimistic (98 % of force errors inside
  // 2 sigma, strain NIS mean 1.92); 1.2e-3 gives 95-97 % and a NIS mean of
  // 1.98-2.09 on every reference scenario (tests/estimator/filter_consistency_test.cc).
  double thrust_scale_psd_1_s = 1.2e-3;       // [1/s]
  double deflection_rate_psd_rad2_s3 = 1e-4;  // on b_i_dot [(rad/s)^2/s]
  double pitch_rate_psd_rad2_s3 = 1e-4;       // on phi_dot [(rad/s)^2/s]
  double omega_psd_rad2_s = 100.0;            // on omega_i [(rad/s)^2/s]
  // Initial one-sigma uncertainties.
  double initial_thrust_scale_std = 0.3;            // [1]
  double initial_omega_std_rad_s = 30.0;            // [rad/s]
  double initial_deflection_rate_std_rad_s = 0.05;  // [rad/s]
  double initial_pitch_rate_std_rad_s = 0.5;        // [rad/s]
  // Chi-square gates, one per measurement, on its normalised innovation
  // squared (NIS = y^T S^-1 y, chi-square with m degrees of freedom): a
  // measurement with a larger NIS is rejected and counted (rejected_gate).
  double strain_gate_nis = 30.0;     // m = 2; p(false reject) = exp(-15) ~ 3e-7 [1]
  double telemetry_gate_nis = 30.0;  // m = 2; as strain [1]
  double gyro_gate_nis = 25.0;       // m = 1; p(false reject) ~ 6e-7 [1]
  double accel_gate_nis = 25.0;      // m = 1; as gyro [1]
  // After this many consecutive gated strain samples the change is taken as
  // real (a step in thrust): var(mu_i) is inflated and the sample fused.
  int gate_consecutive_limit = 3;
  // The inflation: the square of this is added to the variance of each mu_i [1].
  double gate_inflation_thrust_scale_std = 0.1;
  // For this long after a lift-off (the ground contact let go) a pitch rate
  // the gyro gates gate_consecutive_limit times in a row is taken as lost:
  // its variance grows by initial_pitch_rate_std_rad_s^2 and the gyro is
  // fused ungated (not within a thrust step, but within the lift-off's own
  // spin-up, its first step_hold_s). Without it the gentle flight
  // from the ground, seed 1, lost the pitch rate at the lift-off (gyro gated
  // in runs of 4 to 188) and raised MODEL_MISMATCH on the matching vehicle;
  // always on, the hover-infeasible losses counted 2-10x the force
  // fallbacks after their touchdown (docs/mismatch.md) [s]; 0: never.
  double gyro_liftoff_recovery_s = 1.0;
  // Status: kStatusConverging until both force stds fall below this [N].
  double converged_force_std_n = 0.5;
  // Rotor fault: rotor i is weaker than the other rotor j beyond what
  // turbulence explains. Flagged when
  //   (mu_j - mu_i) - n_sigma std(mu_j - mu_i) > rotor_fault_asymmetry
  // for fault_persistence_s; cleared when
  //   (mu_j - mu_i) + n_sigma std(mu_j - mu_i) < rotor_fault_clear_asymmetry.
  // The reference turbulence (1 % per rotor, independent) makes mu_j - mu_i
  // wander with a std of 0.014, so 0.1 is 7 of its sigmas.
  double rotor_fault_asymmetry = 0.1;         // [1]
  double rotor_fault_clear_asymmetry = 0.07;  // [1] (hysteresis)
  // Thrust deficit shared by both rotors (thin air, low battery): flagged
  // (kStatusThrustDeficit, not a rotor fault) when even the stronger rotor has
  //   mu + n_sigma std(mu) < thrust_deficit_scale
  // for fault_persistence_s; cleared when its mu - n_sigma std(mu) > thrust_deficit_clear_scale.
  double thrust_deficit_scale = 0.95;        // [1]
  double thrust_deficit_clear_scale = 0.97;  // [1] (hysteresis)
  double fault_n_sigma = 3.0;                // [1]
  // Three strain samples at 1 kHz: one or two samples' excursion cannot
  // raise a flag; the n_sigma test carries the statistics. 10 ms flagged a
  // quarter thrust loss after 28 ms; 2 ms after 15 ms (9 ms for 40 %), with
  // or without motor telemetry, and no false flag on any reference scenario
  // (issue 27 item 3; tests/estimator/filter_consistency_test.cc) [s].
  double fault_persistence_s = 0.002;
  // N rotors (MultiArmFaultMonitor): within fault_second_rotor_window_s of
  // one rotor's fault going on, a fault on any other rotor must hold
  // fault_second_rotor_persistence_s. After a loss the strain gate's
  // inflation fuses one sample ungated, the thrust scales take the arm's
  // ringing, the next samples are gated again and the inflation repeats
  // every few milliseconds for about 25 ms: a healthy rotor's scale swings
  // past the fault threshold for 2-5 ms (the trirotor, rotor 3 lost, seeds
  // 1 and 5: rotor 2 flagged 16-18 ms after the loss). A real second loss
  // within the window is flagged 4 ms later; none outside it. The birotor's
  // own monitor has one comparison and does not use them [s].
  double fault_second_rotor_persistence_s = 0.006;
  double fault_second_rotor_window_s = 0.05;
  // Strain intervals longer than this are predicted in equal RK4 sub-steps
  // (the pipeline re-initialises the filter after PipelineOptions::reset_gap_s):
  // one RK4 step is only stable and accurate for omega_arm dt well below 2.8
  // (arm modes ~500 rad/s).
  double max_prediction_step_s = 0.002;  // [s]
  // Ground contact (estimator/ground_contact.h): the support force
  // N = (m + 2 m_p) a_z - (f1 + f2), low-passed with this time constant, puts
  // the body on the ground above contact_on_n and back in the air below
  // contact_off_n. 4.5 N is a tenth of the reference weight; the model error
  // of the free-body model on the ground is m_p N / (m + 2 m_p) per rotor
  // (0.07 N at 1 N), so the hysteresis band is where the models nearly agree.
  // 1 N, not 2 N: the trirotor released at 2 N while the ground still held
  // it level against the controller's moment, and 12 VALID estimates before
  // lift-off were beyond 3 sigma (0 at 1 N; the birotor's gauge_offset and
  // gauge_drift MAE 0.1-0.4 % lower; docs/estimator.md, "The EKF for N arms").
  double ground_contact_on_n = 4.5;   // [N]
  double ground_contact_off_n = 1.0;  // [N]
  // [s] (arm modes 65-80 Hz attenuated ~8x); lengthened automatically for a
  // noisy accelerometer (GroundContact::TimeConstantS, from accel_noise_m_s2).
  double ground_contact_filter_s = 0.02;
  // Height above the ground [m] (POSE z over its value while the contact
  // last held) within which the body may still touch it unnoticed: the
  // support can then be anything up to ground_contact_on_n, so the
  // accelerometer's a_z variance gains (ground_contact_on_n / M)^2 there,
  // and the birotor EKF holds its gauge offsets (Schmidt consider states)
  // (docs/estimator.md, "Hovering at the ground's height"). 0: off (the
  // filtered support alone, as without POSE).
  double ground_may_touch_m = 0.02;
  // ... from this long after the contact let go [s]: the lift-off's first
  // moments are read at the accelerometer's full weight, where a payload
  // shows (from the first sample, the band hid a payload at a ground start).
  double ground_may_touch_after_s = 0.5;
  // N arms: while the ground may carry part of the weight (near it, the
  // filtered support above ground_contact_off_n: GroundContact::may_carry),
  // the thrust scale mu_i of a rotor without a gauge is held from every
  // update if its sigma was below this when the episode began (learned in
  // the air); an unlearned one keeps learning, its prior in its sigma.
  // 0: never held (docs/estimator.md, "A rotor without a gauge near the
  // ground"). [1]
  double ground_carry_learned_thrust_scale_std = 0.1;
  // The body is held on a test stand (scenario bench): the supported-body
  // model throughout, whatever the IMU says.
  bool body_held = false;
};

// The tare of the strain gauges (estimator/gauge_tare.h): while the motors
// are stopped and the body rests, each gauge reads s_i b_rest_i + o_i with the
// known rest deflection b_rest_i = -/+ m_p g L / k (birotor_dynamics.h), so
// o_i is the mean reading minus s_i b_rest_i.
struct TareOptions {
  bool enabled = true;
  double window_s = 1.0;              // rest needed for a tare; then refined every window_s [s]
  double motor_stopped_rad_s = 20.0;  // motors stopped: both commands and telemetry below [rad/s]
  double rest_gyro_rad_s = 0.05;      // at rest: |gyro_y| below [rad/s] (10 sigma of the gyro noise)
  double rest_accel_m_s2 = 0.3;       // at rest: ||a| - g| below [m/s^2] (6 sigma of the accel noise)
  double input_timeout_s = 0.05;      // MOTOR and IMU older than this: not judged, no tare [s]
  double max_offset_rad = 5.0e-4;     // |o_i| above this: reading outside the physical range [rad]
  double model_std_rad = 1.0e-6;      // uncertainty of s_i b_rest_i (m_p, k, s_i), added to the mean's [rad]
  // birotor-estimator writes the offsets in use here at a clean stop and
  // starts from them (nodes/gauge_state_file.h); "" for none.
  std::string state_file = "";
};

// The thesis's open-loop model inversion (thesis eq. 5.1-5.2).
struct InversionOptions {
  // Samples in the causal quadratic fit giving b, b_dot, b_ddot (3 = exact
  // interpolation, for noise-free data). 63 is the best of 15, 31 and 63 at
  // the reference noise (force MAE 0.32, 0.16, 0.12 N on gentle): the
  // baseline is measured at its best, not handicapped. At most 64.
  int window_samples = 63;
  // One sigma reported as force_std_n (the inversion has no covariance) [N].
  double force_std_n = 1.0;
};

// The thesis's linear hover model with the forces as random-walk states
// (thesis eq. 4.2, observable part only), discretised at the strain rate;
// shared by the Luenberger observer and the linear Kalman filter. Its noise
// figures are the EKF's (EkfOptions), not options of its own.
struct LinearModelOptions {
  // Nominal strain-gauge sample rate: the model is discretised at 1 / rate;
  // a longer interval is predicted in whole periods (rounded) [Hz].
  double strain_rate_hz = 1000.0;
  // Random walk of each force [N^2/s]. 1.42 is the EKF's former noise figures
  // (thrust_scale_psd 2e-3, omega_psd 100) mapped through f = mu c_T omega^2
  // at hover, and the best hover MAE of 0.3-10 N^2/s; its own key since the
  // EKF's thrust_scale_psd_1_s went to 1.2e-3 (issue 13: the EKF was
  // pessimistic), which would cost the linear KF 1 % of hover MAE.
  double force_psd_n2_s = 1.42;
};

// Gain of the Luenberger observer by pole placement (thesis section 5.4.2,
// made to work): the discrete error matrix (I - L C) A_d gets, in each of the
// two decoupled channels (b_s with f1 - f2, b_d with f1 + f2), the poles
// exp(s T) of the continuous poles below.
struct LuenbergerOptions {
  // Force-error pole s = -2 pi force_bandwidth_hz: how fast a force error
  // decays, against how much strain noise reaches the estimate. 30 Hz is the
  // best hover MAE at the reference noise among 1 to 80 Hz (0.19 N at 1 Hz,
  // 0.14 at 5, 0.091 at 30, 0.106 at 80: turbulence and control move the
  // forces faster than a slow observer follows) [Hz].
  double force_bandwidth_hz = 30.0;
  // Arm-error poles: the channel's own arm mode frequency with this damping
  // ratio (the open arm modes have 0.02) [1].
  double arm_damping_ratio = 0.7;
};

// The nominal motor map f = c_T omega^2.
struct MotorMapOptions {
  double motor_speed_noise_rad_s = 5.0;  // telemetry noise, for force_std_n [rad/s]
  double model_speed_std_rad_s = 10.0;   // omega from the motor model of the commands [rad/s]
};

// Input validation and book-keeping of EstimatorPipeline.
struct PipelineOptions {
  double reset_gap_s = 0.1;             // strain gap that re-initialises the method [s]
  double time_backwards_reset_s = 0.5;  // a jump back larger than this resets (log loop) [s]
  double motor_timeout_s = 0.05;        // newest MOTOR older than this: kStatusInputStale [s]
  double strain_timeout_s = 0.01;       // strain interval longer than this: kStatusInputStale [s]
  double max_deflection_rad = 0.2;      // |b_i| above this is an invalid sample [rad]
  double max_omega_rad_s = 1e4;         // |omega| above this is an invalid sample [rad/s]
  double max_gyro_rad_s = 100.0;        // |gyro| above this is an invalid sample [rad/s]
  // Time outliers: a sample stamped more than this ahead of the newest
  // accepted sample of any input is rejected and counted (time_outliers) and
  // does not move any clock [s]. At the reference rates the inputs are within
  // a few ms of each other; a real jump of every stream (a sender paused on a
  // wall clock) is accepted once forward_jump_confirm_samples consecutive
  // samples agree on it (the ones before are counted as outliers).
  double max_forward_jump_s = 0.05;
  int forward_jump_confirm_samples = 3;
  // Conflicting publishers (two senders on one channel): this many
  // order violations on a channel (a stamp older than or equal to the newest,
  // or seq going backwards) within conflict_window_s raise the conflict
  // (kStatusInputConflict on FORCE, VALID withheld, conflicts counted); it
  // clears after conflict_clear_s without a violation.
  int conflict_min_violations = 5;  // [1]
  double conflict_window_s = 0.1;   // [s]
  double conflict_clear_s = 1.0;    // [s]
};

// Tracked notches against the rotor-harmonic pickup (estimator/harmonic_notch.h).
struct HarmonicNotchOptions {
  bool enabled = true;  // off: the deflection reaches the method unfiltered (the birotor's and N arms')
  // The N-arm pipeline (MultiArmPipeline) notches too when this and enabled
  // are on (docs/estimator.md, "The harmonic notch for N arms").
  bool multi_arm_enabled = true;
  // -3 dB width of each notch [Hz]. 4 Hz: wide against the telemetry noise
  // (5 rad/s is 0.8 Hz at 1x, 1.6 Hz at 2x), narrow enough to leave the arm
  // modes and the thrust_loss detection delay unchanged (8 Hz: +4 ms).
  double bandwidth_hz = 4.0;
  // The N-arm pipeline's -3 dB width [Hz]. A notch answers a step of its
  // arm's deflection (a rotor losing thrust) with a decaying oscillation at
  // its frequency f0 of about bandwidth / f0 of the step for 1 / (pi
  // bandwidth): at 4 Hz on the trirotor's lost rotor 2 (89 Hz), 4.5 % of the
  // step, enough to tip the EKF's split of the loss after its strain gate
  // inflation onto healthy rotor 3 for 3 ms (3 false alarms on
  // thrust_loss); 2 Hz halves it (0 false alarms; docs/estimator.md).
  double multi_arm_bandwidth_hz = 2.0;
  double min_speed_rad_s = 100.0;  // below this rotor speed the notches pass (motors stopped or idling) [rad/s]
  double max_dt_s = 0.01;          // a longer strain interval restarts the notches [s]
};

// Names of the estimation methods (--method, `estimator.method`), in the
// order of the thesis's ladder and the evaluation table: the registry's
// (estimator/estimation_method.cc).
const std::vector<std::string>& EstimationMethodNames();

struct EstimatorConfig {
  // `vehicle:` section; a birotor (BirotorModelOf gives the model its parameters).
  VehicleDescription vehicle = BirotorDescription(BirotorParams());
  std::string method = "ekf";                 // one of EstimationMethodNames()
  EkfOptions ekf;                             // `estimator.ekf:`
  InversionOptions inversion;                 // `estimator.inversion:`
  MotorMapOptions motor_map;                  // `estimator.motor_map:`
  LinearModelOptions linear_model;            // `estimator.linear_model:` (luenberger, linear_kf)
  LuenbergerOptions luenberger;               // `estimator.luenberger:`
  PipelineOptions pipeline;                   // `estimator.pipeline:`
  TareOptions tare;                           // `estimator.tare:`
  HarmonicNotchOptions harmonic_notch;        // `estimator.harmonic_notch:`
  ModelConsistencyOptions model_consistency;  // `estimator.model_consistency:`
};

}  // namespace birotor
