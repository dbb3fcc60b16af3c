// Options of the model-consistency monitor (estimator/model_consistency.h),
// a part of EstimatorConfig (estimator/estimator_config.h): every field has a
// documented default and is loaded from `estimator.model_consistency:` by params/.
#pragma once

namespace birotor {

// The model-consistency monitor (estimator/model_consistency.h, issue 27,
// docs/mismatch.md): when the vehicle does not match its parameter file.
// Per-source arrays are indexed by FusionSource: strain, telemetry, gyro,
// accelerometer.
struct ModelConsistencyOptions {
  // Master switch; false: never raises.
  bool enabled = true;
  // Statistics are taken over consecutive blocks of this length of
  // measurement time (stamps of the reports) [s].
  double window_s = 0.25;
  // A window is inconsistent when, for a source, the mean of NIS/m over its
  // fused reports exceeds its limit (chi-square: mean 1 when the model
  // holds; the matching-file scenarios reach at most 1.52 per 0.25 s window,
  // docs/mismatch.md) [1],
  double nis_ratio_limit[4] = {2.5, 2.5, 2.5, 2.5};
  // ... or the mean of the normalised innovation y/sqrt(S) of its fused
  // reports (0 +- 1/sqrt(n) when white; at most 0.29 on those scenarios)
  // is biased beyond this [1],
  double bias_limit[4] = {1.0, 1.0, 1.0, 1.0};
  // ... or more than this share of its reports was rejected by the gate
  // (a model so wrong that the filter stops fusing an input) [1].
  double rejected_share_limit = 0.2;
  // Fewer reports than this in a window: that source is not judged.
  int min_reports = 20;
  // Raised after this many inconsistent windows in a row (2: a single
  // window of a rotor fault's step or a lift-off transient is not a
  // mismatch); cleared after clear_windows consistent ones.
  int raise_windows = 2;
  int clear_windows = 8;
  // Fast test for overwhelming evidence (the windows above take 0.5 s): a
  // two-sided CUSUM of the accelerometer's normalised innovation z =
  // y/sqrt(S), over every report with an innovation (fused or gated: the
  // mismatched vehicles are gated from the first sample), each z clipped to
  // +-fast_cusum_clip,
  //   C+ = max(0, C+ + z - fast_cusum_drift),  C- = max(0, C- - z - fast_cusum_drift),
  // raised at once when C+ or C- exceeds fast_cusum_limit; 0 switches it
  // off. The accelerometer weighs the total force against the file's mass,
  // which every mismatch of stiffness, gauge scale or mass breaks from the
  // first samples (z 7-12 and more); the gyro does not for half of them.
  // With clip 5 (the accelerometer's gate, sqrt(accel_gate_nis)) and drift
  // 2 every sample at the gate adds 3, white noise nothing lasting. Measured
  // (tests/estimator/mismatch_scenarios_test.cc, docs/mismatch.md): largest
  // C on the matching-file scenarios 15.9 (thrust_loss_severe's step; 15.0
  // thrust_loss, 11.0 gauge_offset's lift-off, <= 2.8 elsewhere), smallest
  // peak on the mismatched ones 51 (all at once; 63-75 where the gyro
  // diverges too, 45000 elsewhere): 30 is 1.9x above the one and 1.7x
  // below the other, and raises 11 ms after the first estimate.
  double fast_cusum_clip = 5.0;    // [1]
  double fast_cusum_drift = 2.0;   // [1]
  double fast_cusum_limit = 30.0;  // [1]
  // After start the model counts as confirmed after this many consistent
  // windows in a row (THRUST_DEFICIT waits for it). A filter reset (gap,
  // time jump) keeps what was confirmed or raised: the vehicle did not change.
  int confirm_windows = 2;
  // Whether VALID waits for that confirmation too. false by default: the
  // closed loop flies on VALID forces from the first tens of ms; waiting
  // 0.5 s raised the peak altitude loss of the density flight from 0.0169 to
  // 0.0725 m and of the severe loss from 0.0095 to 0.208 m
  // (tests/evaluation/closed_loop_test.cc). The fast test above is what
  // keeps a grossly mismatched vehicle from being VALID meanwhile.
  bool valid_needs_confirmation = false;
  // Attribution: with the accelerometer (or gyro) inconsistent, a window
  // mean of a thrust scale mu_i further than this from 1 points at the
  // stiffness or gauge scale, closer at the mass (measured at 0.5 s:
  // body mass +-15 % at most 0.069, stiffness +-20 %, gauge scale 0.7 / 1.3
  // and all at once at least 0.078; docs/mismatch.md) [1].
  double thrust_scale_deviation = 0.075;
  // The arm-mode test (estimator/arm_mode_monitor.h): the frequency of the
  // arms' symmetric mode (b1 - b2) in free flight against the file's
  // (model/linearization.h: 65.03 Hz on the reference file). A tip-mass
  // error moves it (sqrt(m_p / m_p_true): -8.7 % for +20 %, +11.8 % for
  // -20 %) without any static inconsistency the tests above could see.
  // false: off.
  bool arm_mode_enabled = true;
  // Relative frequency error |f / f_file - 1| beyond which a flight is
  // inconsistent for arm_mode_raise_s. What lasts that long: on the matching
  // files and the c_T / tau_m mismatches at most 0.020-0.025 (a limit of
  // 0.020 raises sensor_faults, 0.025 nothing; the largest single reading
  // is 0.040), on tip mass +20 % 0.055-0.060 (a limit of 0.055 raises it at
  // 0.852 s, 0.060 at 2.54 s). 0.040 is 1.6-2.0x above the one and
  // 1.4-1.5x below the other (docs/mismatch.md) [1].
  double arm_mode_limit = 0.040;
  // Raised when beyond the limit for this long; cleared when within half of
  // it for arm_mode_clear_s [s].
  double arm_mode_raise_s = 0.25;
  double arm_mode_clear_s = 2.0;
  // Estimator: two band-pass biquads of this quality at the file's
  // frequency, then an AR(2) least-squares fit weighted with this time
  // constant; the first fit after arm_mode_settle_s + the time constant of
  // airborne samples [1], [s].
  double arm_mode_band_q = 2.0;
  double arm_mode_time_constant_s = 0.5;
  double arm_mode_settle_s = 0.1;
  // Judged only while the band's mean square is at least this many times
  // the gauge noise's through the same band-pass (EkfOptions::
  // strain_noise_rad, times the EKF's learned scale on its variance,
  // adapt_strain_noise): noise alone reads the band-pass, not the arm
  // (+10 % in tests/estimator/arm_mode_monitor_test.cc). Noise alone reaches
  // 1.0-1.25, the flights 2.5-6.8 (docs/mismatch.md) [1].
  double arm_mode_min_excitation = 1.5;
  // The same for the N-arm pipeline (birotor-estimator --vehicle): its
  // mode's combination of gauges reads the noise's pull further from the
  // mode (the trirotor in a calm hover, turbulence 0.002: a matching
  // vehicle reads up to +10 % at 1.5, +4 % at 2.5; its ordinary flights
  // ring the mode 11-15 times the noise) [1].
  double arm_mode_multi_arm_min_excitation = 3.0;
  // Whether VALID waits while the arm mode has not confirmed the tip mass
  // (ArmModeState::awaiting_reading: 1.1 s after lift-off on a flight
  // whose mode agrees). false by default: the unconfirmed tip mass widens
  // the sigma instead (below), and a daemon restarted in flight must be
  // VALID within 0.5 s (docs/reliability.md); true keeps a tip-mass error
  // from ever being VALID (docs/mismatch.md).
  bool arm_mode_valid_needs_reading = false;
  // Until the arm mode confirms the file's tip mass (ArmModeState::agreed:
  // the mean of the readings within half the limit, ReadingAgreement; in the
  // air from lift-off, and for good on a flight whose mode is too quiet to
  // read), each published force sigma includes this relative 1-sigma
  // uncertainty of the tip mass: sigma^2 + (std m_p g)^2 at hover. The rigid body cannot
  // see a tip-mass error (docs/mismatch.md), so before the reading the
  // estimate is only as good as the file's m_p. 0.15: a propeller or motor
  // change moves m_p by 10-20 %; a 20 % error lies at 1.3 sigma. Tip mass
  // +-20 %, worst 2 s VALID share: 0.10 gives 0.62 / 0.56, 0.12 0.93 / 0.91,
  // 0.15 1.000 / 0.999 (docs/mismatch.md) [1].
  double arm_mode_unconfirmed_tip_mass_std = 0.15;
  // Learning the tip mass (issue 36; estimator/tip_mass_learning.h,
  // docs/mismatch.md "Learning the tip mass"): the arm mode's readings give
  // m_p with a sigma (a 1-D filter on m_p / m_p_file, prior 1 +-
  // arm_mode_unconfirmed_tip_mass_std); the EKF flies it averaged with the
  // file's (next key), each airborne force sigma carries its sigma (x m_p
  // g), and MODEL_MISMATCH is raised only for a mode no tip mass within
  // arm_mode_explained_sigmas prior sigmas explains (a broken arm). Not with
  // learn_strain_scale (a learned g may be a stiffness) nor for a method
  // that does not fly m_p (ForceEstimator::flies_tip_mass): there, and with
  // false, the file's m_p judged against the file's mode (issue 27's test).
  bool arm_mode_learn_tip_mass = true;
  // Prior probability that the tip mass is not the file's (H1; H0: the
  // file's m_p exactly; estimator/parameter_hypotheses.h): learning flies
  // the average of the file's and the learned m_p by P(H1 | readings), so a
  // matching vehicle flies the file's (MAE as unlearned) and a tip mass 5 %
  // off the learned one within seconds (docs/mismatch.md) [1].
  double arm_mode_tip_mass_change_probability = 0.1;
  // Once the readings confirm the file's mode, P(H1) below this flies the
  // file's m_p with no tip-mass sigma, as without learning [1].
  double arm_mode_tip_mass_file_accepted_below = 0.1;
  // Relative sigma of one independent reading (one per 2 time constants)
  // of the mode, freed of the band-pass's pull [1]. 0.015: the matching
  // files' EW readings (-1.9 % to +2.8 %) x 1 / pull; 0.008 keeps the
  // matching flights' 2-sigma share at 0.955-0.963 (0.015: 0.965-0.978) but
  // makes gauge noise x2 and the calm hovers over-confident
  // (birotor-eval --mismatch-targets --seeds 5, docs/mismatch.md).
  double arm_mode_reading_std = 0.015;
  // Relative 1-sigma bias every reading of a mode read on some arms only
  // shares (an arm without a gauge, GaugedModalWeights): the rest of the
  // vehicle's motion leaks into the combination, which no number of
  // readings averages away; it is carried in the learned tip mass's sigma
  // (TipMassLearner). The trirotor without arm 2's or 3's gauge reads a
  // matching vehicle's 64.6 Hz mode 0.2-1.2 % high and learns r 0.783 for
  // a tip mass 20 % light (docs/estimator.md "Two gauges of three"); 0.01
  // brings that flight's 2-sigma share from 0.854 to 0.945. Every arm
  // gauged: not used [1].
  double arm_mode_partial_gauge_reading_bias = 0.01;
  // The band-pass pulls a reading towards its centre: it reads c + p (f - c)
  // for a mode f. The synthetic test reads -8.7 % as -6.6 % to -7.8 %, the
  // flights tip mass +20 % (-7.6 %) mostly -5 % to -6 %: p = 0.75 [1]. The
  // band-pass follows the learned mode, where the pull vanishes.
  double arm_mode_band_pull = 0.75;
  // A reading beyond the modes of every m_p within this many prior sigmas
  // (3 x 0.15: m_p 0.55-1.45 x the file's, 56.1-73.8 Hz on the reference
  // file) by more than arm_mode_limit for arm_mode_raise_s: MODEL_MISMATCH [1].
  double arm_mode_explained_sigmas = 3.0;
  // The tip mass learns only from readings whose band holds at least this
  // many times the gauge noise's power (arm_mode_min_excitation judges):
  // noise pulls a reading towards the band-pass's centre (docs/mismatch.md) [1].
  double arm_mode_learn_min_excitation = 3.0;
  // The offset-departure test (estimator/offset_departure.h): MODEL_MISMATCH
  // ("mass") when the gauge offsets learned in free flight leave their anchor
  // (the file's, a tare's, a state file's) along the direction a common force
  // deflects the arms by more than this many sigmas of their prior and drift,
  // for offset_departure_hold_s; held until the next tare. A payload the file
  // lacks goes there: body +10 % airborne reads 4.1-5.4 sigma on every seed
  // (VALID and 1.96 N off without the test) (docs/mismatch.md) [sigma]; 0: off.
  // Near the ground each gauge's own departure is judged by it too
  // ("stiffness_or_gauge_scale": a support the contact test did not see).
  double offset_departure_limit = 4.0;
  double offset_departure_hold_s = 0.1;  // [s]
  // Below that limit the offsets' departure along the same direction is
  // still what a payload would make: its share beyond this many sigmas,
  // (|z| - this) / |z| of the departure, is carried in each published force
  // sigma as the force it would be (ConsistencyStatusFacts::
  // offset_force_std_n). Without it a payload of 3-7 % of the body (within
  // the limit) was VALID, 0.6-1.4 N off, 2-sigma share 0.00; at 0 the
  // offsets a real gauge starts with in the air (gauge_airborne) widened
  // the sigma to a share of 1.000 (docs/mismatch.md) [sigma]; negative: off.
  double offset_departure_in_sigma_above = 0.5;
  // What learned strain scales are (estimator.ekf learn_strain_scale with
  // the tip mass learned; estimator/strain_scale_attribution.h,
  // docs/mismatch.md "What a learned strain scale is"): the priors of a
  // change of both arms' stiffness and of one gauge's scale (relative, one
  // sigma; a tip mass's is arm_mode_unconfirmed_tip_mass_std, a payload's
  // estimator.ekf body_mass_scale_prior_std, each change's probability
  // arm_mode_tip_mass_change_probability) [1].
  double scale_attribution_stiffness_std = 0.2;
  double scale_attribution_gauge_scale_std = 0.2;
  // The model's tolerance on the evidence (ln g's mean and difference, the
  // mode's log-frequency shift), one sigma: the hover linearisation's mode
  // against a flight's [1].
  double scale_attribution_tolerance = 0.02;
  // Beyond this Mahalanobis distance^2 of the evidence under the best single
  // change none explains the scales and the mode (several changes at once):
  // MODEL_MISMATCH `stiffness_or_gauge_scale`. Measured: at most 4.0 for one
  // change (gentle, seeds 1-5: stiffness +-15/20 %, gauge 0.7 on either
  // arm, tip mass +-20 %), 7.6 for mismatch_all, 25-33 for every parameter
  // 5-30 % off [1].
  double scale_attribution_limit = 6.0;
  // A payload's weight above which (held offset_departure_hold_s)
  // MODEL_MISMATCH "mass" is raised: the forces are the payload's share off
  // (the accelerometer weighs them against the file's mass). 0.3: a body
  // +10 % reads 0.3-0.8 from the split of scales and offsets on, the calm
  // hovers (whose g wanders unobserved) at most 0.11 [1].
  double scale_attribution_payload_weight = 0.3;
  // The weight at which a stiffness, a gauge's scale or a tip mass (not a
  // payload) explains the scales: a payload's MODEL_MISMATCH is released,
  // and with the file's vehicle too an offsets' departure neither holds
  // nor widens [1].
  double scale_attribution_stand_weight = 0.8;
};

}  // namespace birotor
