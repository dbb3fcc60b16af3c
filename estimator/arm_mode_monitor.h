// Arm-mode frequency monitor (issue 27): the one mismatch the rigid body
// cannot see. A tip-mass error reads as a thrust-map error to the
// accelerometer and the gyro (docs/mismatch.md), but it moves the arms'
// symmetric mode (k over the tip inertia, 65.03 Hz on the reference file)
// by sqrt(m_p / m_p_true). This monitor estimates that frequency from the
// strain samples in free flight and flags a sustained departure from the
// file's. Any described vehicle: the arm mode the turbulence rings most
// above the gauge noise, read from the gauge combination that holds it
// alone (model/multi_arm_modes.h; the birotor's symmetric mode in b1 - b2). Pure library: no LCM, no logging, no
// allocation per sample.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "estimator/arm_mode_expectation.h"
#include "estimator/estimator_config.h"
#include "estimator/reading_agreement.h"
#include "estimator/tip_mass_learning.h"
#include "model/birotor_params.h"
#include "model/vehicle_description.h"
#include "samples/multi_arm_samples.h"
#include "samples/rotor_count.h"

namespace birotor {

// The frequency of a damped resonance in a sampled signal: two band-pass
// biquads (RBJ, centre centre_hz, quality q, in cascade) and an AR(2) fit by
// exponentially weighted least squares, y[n] = c1 y[n-1] + c2 y[n-2]; the
// pole pair r e^(+-j w) gives f = w / (2 pi dt) (c1 = 2 r cos w, c2 = -r^2).
// The band-pass pulls the estimate towards its centre (on the reference
// flights a true shift of -8.7 % / +11.8 % reads -6.5 % / +7.7 %), which
// the limit of the monitor accounts for.
class ResonanceFrequencyEstimator {
 public:
  // Designs the filters for sample interval dt_s; forgets everything.
  void Start(double centre_hz, double q, double time_constant_s, double dt_s, double first_sample);
  // Moves the band-pass's centre, keeping the filters' state and the sums
  // (a learned tip mass moves the mode: centred on it, the band-pass does
  // not pull the reading).
  void Recentre(double centre_hz);
  void Add(double sample);
  // Forgets the fit's sums (the filters keep their state).
  void ForgetSums();
  // NaN while the weighted sums hold no resonance (no pole pair).
  // excess_noise: the std of white noise in the samples beyond what the
  // caller's limits were set with; its expected share is taken out of the
  // sums first (noise pulls the reading towards the band-pass) [unit of
  // the samples].
  double FrequencyHz(double excess_noise = 0) const;
  // Weighted mean square of the band-passed signal over that of white noise
  // of standard deviation noise through the same band-pass: 1 for noise
  // alone, well above when the resonance is excited [1].
  double Excitation(double noise) const;
  double time_constant_s() const { return time_constant_s_; }
  double centre_hz() const { return centre_hz_; }

 private:
  // The band-pass's coefficients for centre_hz, and its noise gains.
  void Design(double centre_hz);
  struct Biquad {
    double b0 = 0, b2 = 0, a1 = 0, a2 = 0;  // b1 = 0 (band-pass)
    double x1 = 0, x2 = 0, y1 = 0, y2 = 0;  // direct form I
    double Apply(double x);
  };
  Biquad stage_[kBirotorRotors];
  double dt_s_ = 1e-3;
  double centre_hz_ = 0;  // of the band-pass [Hz]
  double q_ = 2;          // of each biquad [1]
  double time_constant_s_ = 0.5;
  double forget_ = 1.0;                               // exp(-dt / time constant) per sample
  double noise_gain_ = 1;                             // sum of the band-pass's squared impulse response [1]
  double noise_lag1_gain_ = 0, noise_lag2_gain_ = 0;  // sums of h_n h_(n-1), h_n h_(n-2) [1]
  double weight_sum_ = 0;                             // sum of the weights of the sums below [1]
  double s00_ = 0;                                    // weighted sum of y^2
  double y1_ = 0, y2_ = 0;
  // Weighted sums: s11 = sum y1^2, s12 = sum y1 y2, s22 = sum y2^2,
  // s01 = sum y y1, s02 = sum y y2.
  double s11_ = 0, s12_ = 0, s22_ = 0, s01_ = 0, s02_ = 0;
};

struct ArmModeState {
  ArmModeExpectation expected;  // of the parameter file [Hz]
  // The newest estimate; NaN when none yet (on the ground, warming up) [Hz].
  double frequency_hz = 0;
  // frequency_hz / expected.low_hz - 1 below the range, frequency_hz /
  // expected.high_hz - 1 above it, 0 within it or when none [1].
  double relative_error = 0;
  // The band's mean square over the gauge noise's (ResonanceFrequencyEstimator::
  // Excitation); judged only above arm_mode_min_excitation [1].
  double excitation = 0;
  double lowest_excitation = 0;  // lowest judged since start-up (0: none) [1]
  double statistic = 0;          // |relative_error| / arm_mode_limit [1] (> 1: beyond the limit)
  double peak_abs_error = 0;     // largest |relative_error| since start-up [1]
  bool mismatch = false;         // a sustained error beyond the limit holds
  // The readings since start-up confirm the tip mass in use (ReadingAgreement;
  // kept over resets and landings: the vehicle did not change).
  bool agreed = false;
  // Not agreed yet, in free flight, and the mode read or its first reading
  // not due yet: VALID waits when arm_mode_valid_needs_reading. false on the
  // ground and while the mode is too quiet to read (nothing would come) [bool].
  bool awaiting_reading = false;
  int64_t raised_utime = -1;  // when the current (or last) one was raised [us]; -1 never
  int64_t raised_count = 0;
  // Learning the tip mass (arm_mode_learn_tip_mass, docs/mismatch.md
  // "Learning the tip mass"): the readings are turned into m_p with a
  // sigma (TipMassLearner), the filter flies the learned m_p, and a
  // reading is judged against every mode a tip mass within
  // arm_mode_explained_sigmas prior sigmas explains. false: the file's
  // m_p, judged against the file's mode (the test of issue 27).
  bool learning = false;
  double tip_mass_kg = 0;         // the m_p in use: the file's, or learned (averaged with the file's) [kg]
  double tip_mass_ratio = 1;      // that m_p over the file's (every arm's, for N arms) [1]
  double tip_mass_ratio_std = 0;  // its one sigma [1]
  double tip_mass_std_kg = 0;     // its one sigma (the prior's before a reading) [kg]
  // Learning: the readings' mean confirms the file's m_p (ReadingAgreement
  // against the file's mode, whatever the learned m_p; kept for good) [bool].
  bool file_tip_mass_agreed = false;
  // Learning: P(the tip mass is not the file's | readings), the learned
  // m_p's weight in tip_mass_kg (1 before this run's first reading) [1].
  double tip_mass_change_probability = 0;
  // Learning: the learner's own r = m_p / m_p,file read from the mode with
  // the file's stiffness and its sigma, before the average with the file's
  // (what the mode says; estimator/strain_scale_attribution.h) [1].
  double learned_ratio = 1;
  double learned_ratio_std = 0;
  // The relative sigma of m_p each published force sigma carries now (0:
  // none): learning, the learned one while airborne; else the prior's
  // (arm_mode_unconfirmed_tip_mass_std) while airborne and not agreed, a
  // mode too quiet to read included (it confirms nothing) [1].
  double force_tip_mass_std = 0;
  double centre_hz = 0;  // of the band-pass: the file's mode, or the learned m_p's [Hz]
  // Readings the learned m_p took in this run (0: still the prior's, or the
  // value resumed from the state file) [1].
  int64_t tip_mass_readings = 0;
  // The readings' mean rejected the m_p resumed from the state file (the
  // vehicle changed since: a propeller or motor swapped): learning restarted
  // from the file's m_p and the prior (TipMassLearner::Forget) [bool].
  bool resumed_tip_mass_rejected = false;
};

class ArmModeMonitor {
 public:
  // expected: ExpectedArmMode of the file; noise_rad: the gauges' noise per
  // arm (EkfOptions::strain_noise_rad); the options arm_mode_*; tip_mass:
  // the model's mode over m_p (empty: the tip mass is not learned).
  ArmModeMonitor(const ModelConsistencyOptions& options, const ArmModeExpectation& expected, double noise_rad,
                 const ArmModeTipMassMap& tip_mass = ArmModeTipMassMap());
  // One strain sample as the method got it (calibrated, notched; the
  // expectation's `arms` readings, a NaN reading of a weighted arm taken as
  // an outlier) [rad];
  // airborne: the method's ground contact says free flight (on the ground
  // the modes are those of the contact: no test); outlier: the method's gate
  // rejected it (a spike would ring the band-pass; the previous value is
  // used). Returns whether a mismatch holds. Without a test for the
  // vehicle (expected.file_hz 0) it only keeps the tip mass's prior
  // (arm_mode_unconfirmed_tip_mass_std) as force_tip_mass_std while airborne.
  bool Add(int64_t utime, const double* deflection_rad, bool airborne, bool outlier);
  // The filter was re-initialised (gap, time jump): the estimate restarts;
  // a raised mismatch stays (the vehicle did not change).
  void Restart();
  const ArmModeState& state() const { return state_; }
  // What the mode may be now (WithLearnedStrainScales while the EKF learns
  // strain scales); the band-pass stays centred on the file's.
  void SetExpected(const ArmModeExpectation& expected) { state_.expected = expected; }
  // The gauges' noise variances are scale_i times the file's (the EKF's
  // learned strain noise; one per arm of the expectation): the excitation
  // is judged against that noise.
  void SetStrainNoiseScales(const double* scale);
  // Learning starts from an earlier run's m_p and its sigma (the gauge state
  // file; TipMassLearner::Resume), the band-pass centred on its mode. False
  // (nothing changed) when the tip mass is not learned here.
  bool ResumeTipMass(double tip_mass_kg, double std_kg);
  // The test runs (switched on, and a file's frequency to judge against).
  bool active() const { return options_.arm_mode_enabled && state_.expected.file_hz > 0; }

 private:
  void Judge(int64_t utime, double frequency_hz);
  // The learned tip mass takes the reading; the relative error of the
  // reading against what a tip mass within the prior explains, and the
  // signed one against the learned m_p's mode [1].
  void Learn(double frequency_hz, double* relative_error, double* agreement_error);
  // Learning now: switched on, a model, and a stiffness the file fixes
  // (no learned strain scale that may be a stiffness widens the expectation).
  bool Learning() const { return learner_.active() && state_.expected.low_hz == state_.expected.high_hz; }
  // The tip-mass fields of state_ (learned value, sigmas) after a sample.
  void UpdateTipMass();
  // Ends the current airborne run of samples: no reading, nothing awaited.
  void ForgetRun();
  // The readings against a resumed m_p: kept once they confirm it; learning
  // restarts from the file's m_p once they reject it.
  void JudgeResumedTipMass(double corrected_hz);
  // A reading freed of the band-pass's pull as the error a band-pass
  // centred on mode_hz reads it with: p (f_c / mode - 1), what the test
  // without learning holds against the limit [1].
  double PulledError(double corrected_hz, double mode_hz) const;

  // The mode's signal sum_i w_i b_i of a sample (the previous one for an
  // outlier or a missing reading).
  double Signal(const double* deflection_rad, bool outlier) const;

  ModelConsistencyOptions options_;
  int arms_;                 // readings the signal combines
  ArmValues weights_;        // w_i of the signal [1]
  double weight_norm2_ = 0;  // sum_i w_i^2 [1]
  double file_noise_rad_;    // a gauge's noise in the file [rad]
  ArmValues noise_scale_{};  // on each gauge's variance [1]
  double noise_rad_;         // of the signal: sqrt(sum_i w_i^2 scale_i) times a gauge's [rad]
  // Of the signal beyond the file's noise, sqrt(sum_i w_i^2 (scale_i - 1))
  // times a gauge's: taken out of the fit, so the reading is what it would
  // be with the file's noise, which arm_mode_limit was set with [rad].
  double excess_noise_rad_ = 0;
  ResonanceFrequencyEstimator estimator_;
  TipMassLearner learner_;
  // Lowest and highest mode a tip mass within arm_mode_explained_sigmas
  // prior sigmas of the file's explains [Hz].
  double explained_low_hz_ = 0, explained_high_hz_ = 0;
  double file_mode_hz_ = 0;  // of the file's m_p on the map [Hz]
  ArmModeState state_;
  int64_t previous_utime_ = -1;
  int64_t start_utime_ = -1;  // of the current airborne run of samples; -1 none
  double dt_s_ = 0;           // sample interval the filters were designed for [s]
  double previous_signal_ = 0;
  int64_t beyond_since_ = -1;        // first utime of the current run beyond the limit; -1 none
  int64_t within_since_ = -1;        // ... within half the limit; -1 none
  ReadingAgreement agreement_;       // of every reading judged since start-up
  ReadingAgreement file_agreement_;  // learning: of the readings against the file's mode
  // Learning from a resumed m_p: the readings against its mode, until they
  // confirm or reject it (resumed_mode_hz_ 0: nothing resumed, or judged).
  ReadingAgreement resumed_agreement_;
  double resumed_mode_hz_ = 0;  // [Hz]
};

}  // namespace birotor
