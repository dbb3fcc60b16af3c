// The symmetric arm mode's frequency in flight against the file's.
#include "estimator/arm_mode_monitor.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "estimator/parameter_hypotheses.h"

namespace birotor {
namespace {

// The band-pass is moved to the learned mode when they differ by more than
// this in ln f [1].
constexpr double kRecentreStep = 0.005;

}  // namespace

double ResonanceFrequencyEstimator::Biquad::Apply(double x) {
  const double y = b0 * x + b2 * x2 - a1 * y1 - a2 * y2;
  x2 = x1;
  x1 = x;
  y2 = y1;
  y1 = y;
  return y;
}

void ResonanceFrequencyEstimator::Start(double centre_hz, double q, double time_constant_s, double dt_s,
                                        double first_sample) {
  dt_s_ = dt_s;
  q_ = q;
  time_constant_s_ = time_constant_s;
  forget_ = std::exp(-dt_s / time_constant_s);
  for (Biquad& s : stage_) s = Biquad();
  Design(centre_hz);
  // Started in the steady state of a constant input first_sample (its
  // output is 0: no zero at DC), so the start does not ring.
  stage_[0].x1 = stage_[0].x2 = first_sample;
  y1_ = y2_ = 0;
  ForgetSums();
}

void ResonanceFrequencyEstimator::Recentre(double centre_hz) { Design(centre_hz); }

void ResonanceFrequencyEstimator::Design(double centre_hz) {
  centre_hz_ = centre_hz;
  // RBJ band-pass (constant 0 dB peak gain): H = alpha (1 - z^-2) / (a0 + a1 z^-1 + a2 z^-2),
  // alpha = sin(w0) / (2 q).
  const double w0 = 2.0 * M_PI * centre_hz * dt_s_;
  const double alpha = std::sin(w0) / (2.0 * q_);
  const double a0 = 1.0 + alpha;
  for (Biquad& s : stage_) {
    s.b0 = alpha / a0;
    s.b2 = -alpha / a0;
    s.a1 = -2.0 * std::cos(w0) / a0;
    s.a2 = (1.0 - alpha) / a0;
  }
  // The noise gain: the squared impulse response summed until it has decayed
  // (once per start or re-centring, not per sample).
  // With it the lag-1 and lag-2 sums h_n h_(n-1), h_n h_(n-2): white noise
  // of variance v reads v times these in y y1 and y y2.
  Biquad impulse[kBirotorRotors] = {stage_[0], stage_[1]};
  for (Biquad& s : impulse) s.x1 = s.x2 = s.y1 = s.y2 = 0;
  noise_gain_ = noise_lag1_gain_ = noise_lag2_gain_ = 0;
  double h1 = 0, h2 = 0;
  for (int n = 0; n < 4096; ++n) {
    const double h = impulse[1].Apply(impulse[0].Apply(n == 0 ? 1.0 : 0.0));
    noise_gain_ += h * h;
    noise_lag1_gain_ += h * h1;
    noise_lag2_gain_ += h * h2;
    h2 = h1;
    h1 = h;
  }
}

void ResonanceFrequencyEstimator::ForgetSums() { weight_sum_ = s00_ = s11_ = s12_ = s22_ = s01_ = s02_ = 0; }

double ResonanceFrequencyEstimator::Excitation(double noise) const {
  const double noise_power = noise * noise * noise_gain_;
  return weight_sum_ > 0 && noise_power > 0 ? s00_ / weight_sum_ / noise_power : 0.0;
}

void ResonanceFrequencyEstimator::Add(double sample) {
  const double y = stage_[1].Apply(stage_[0].Apply(sample));
  const double f = forget_;
  weight_sum_ = f * weight_sum_ + 1.0;
  s00_ = f * s00_ + y * y;
  s11_ = f * s11_ + y1_ * y1_;
  s12_ = f * s12_ + y1_ * y2_;
  s22_ = f * s22_ + y2_ * y2_;
  s01_ = f * s01_ + y * y1_;
  s02_ = f * s02_ + y * y2_;
  y2_ = y1_;
  y1_ = y;
}

double ResonanceFrequencyEstimator::FrequencyHz(double excess_noise) const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // The excess noise's expected share of each sum (variance v = excess^2,
  // weighted like the sums): v W g0 in s11, s22; v W g1 in s12, s01; v W g2 in s02.
  const double v = excess_noise * excess_noise * weight_sum_;
  const double s11 = s11_ - v * noise_gain_, s22 = s22_ - v * noise_gain_;
  const double s12 = s12_ - v * noise_lag1_gain_, s01 = s01_ - v * noise_lag1_gain_;
  const double s02 = s02_ - v * noise_lag2_gain_;
  // Normal equations [s11 s12; s12 s22] [c1; c2] = [s01; s02] (Cramer).
  const double det = s11 * s22 - s12 * s12;
  if (!(det > 0)) return nan;
  const double c1 = (s01 * s22 - s02 * s12) / det;
  const double c2 = (s11 * s02 - s12 * s01) / det;
  if (!(c2 < 0)) return nan;  // no complex pole pair
  const double cos_w = c1 / (2.0 * std::sqrt(-c2));
  if (!(std::fabs(cos_w) < 1.0)) return nan;
  return std::acos(cos_w) / (2.0 * M_PI * dt_s_);
}

ArmModeMonitor::ArmModeMonitor(const ModelConsistencyOptions& options, const ArmModeExpectation& expected,
                               double noise_rad, const ArmModeTipMassMap& tip_mass)
    : options_(options),
      arms_(std::clamp(expected.arms, 1, kMaxSampleArms)),
      weights_(expected.weights),
      file_noise_rad_(noise_rad) {
  for (int i = 0; i < arms_; ++i) weight_norm2_ += weights_[static_cast<size_t>(i)] * weights_[static_cast<size_t>(i)];
  noise_scale_.fill(1.0);
  noise_rad_ = std::sqrt(weight_norm2_) * noise_rad;  // the birotor's b1 - b2: sqrt(2) times a gauge's
  state_.expected = expected;
  state_.frequency_hz = std::numeric_limits<double>::quiet_NaN();
  state_.centre_hz = expected.file_hz;
  if (options.arm_mode_learn_tip_mass && !tip_mass.empty()) {
    TipMassLearner::Options learning;
    learning.prior_std = options.arm_mode_unconfirmed_tip_mass_std;
    learning.reading_std = options.arm_mode_reading_std;
    learning.band_pull = options.arm_mode_band_pull;
    learning.reading_bias = expected.read_on_some_gauges ? options.arm_mode_partial_gauge_reading_bias : 0.0;
    learner_ = TipMassLearner(learning, tip_mass);
    const double spread = options.arm_mode_explained_sigmas * learning.prior_std;
    explained_low_hz_ = std::exp(tip_mass.LogHz(1.0 + spread));
    explained_high_hz_ = std::exp(tip_mass.LogHz(std::max(1.0 - spread, ArmModeTipMassMap::kLowestRatio)));
    file_mode_hz_ = std::exp(tip_mass.LogHz(1.0));
    state_.tip_mass_kg = tip_mass.file_tip_mass_kg();
    state_.tip_mass_std_kg = learning.prior_std * state_.tip_mass_kg;
  }
}

bool ArmModeMonitor::ResumeTipMass(double tip_mass_kg, double std_kg) {
  if (!learner_.Resume(tip_mass_kg, std_kg)) return false;
  resumed_mode_hz_ = learner_.LearnedHz();
  resumed_agreement_ = ReadingAgreement();
  state_.tip_mass_kg = learner_.tip_mass_kg();
  state_.tip_mass_std_kg = learner_.ratio_std() * learner_.map().file_tip_mass_kg();
  state_.centre_hz = learner_.LearnedHz();  // the next run of samples starts its band-pass there
  return true;
}

void ArmModeMonitor::Restart() {
  previous_utime_ = -1;
  ForgetRun();
}

void ArmModeMonitor::ForgetRun() {
  start_utime_ = -1;
  beyond_since_ = within_since_ = -1;
  state_.frequency_hz = std::numeric_limits<double>::quiet_NaN();
  state_.relative_error = state_.statistic = 0;
  state_.awaiting_reading = false;
  state_.force_tip_mass_std = 0;
}

void ArmModeMonitor::SetStrainNoiseScales(const double* scale) {
  bool same = true;
  for (int i = 0; i < arms_; ++i) same = same && scale[i] == noise_scale_[static_cast<size_t>(i)];
  if (same) return;
  double weighted = 0;  // sum_i w_i^2 scale_i [1]
  for (int i = 0; i < arms_; ++i) {
    const size_t k = static_cast<size_t>(i);
    noise_scale_[k] = scale[i];
    weighted += weights_[k] * weights_[k] * scale[i];
  }
  noise_rad_ = file_noise_rad_ * std::sqrt(weighted);
  excess_noise_rad_ = file_noise_rad_ * std::sqrt(std::max(weighted - weight_norm2_, 0.0));
}

double ArmModeMonitor::Signal(const double* deflection_rad, bool outlier) const {
  if (outlier) return previous_signal_;
  // The birotor's b1 - b2: the symmetric mode (arm 1 reads -delta, arm 2
  // +delta at hover); the antisymmetric one (79.75 Hz on the file) cancels.
  double signal = 0;
  for (int i = 0; i < arms_; ++i) {
    const double w = weights_[static_cast<size_t>(i)];
    if (w != 0.0) signal += w * deflection_rad[i];
  }
  return std::isfinite(signal) ? signal : previous_signal_;
}

bool ArmModeMonitor::Add(int64_t utime, const double* deflection_rad, bool airborne, bool outlier) {
  if (!active()) {
    // A vehicle without the test (file_hz 0: an arm without a gauge, or no
    // mode that rings alone, the quadrotor): nothing confirms its file's tip
    // mass in the air, so the prior stays in the sigma while airborne.
    const bool no_test_here = state_.expected.file_hz == 0;
    state_.force_tip_mass_std = no_test_here && airborne ? options_.arm_mode_unconfirmed_tip_mass_std : 0.0;
    return false;
  }
  const int64_t previous_utime = previous_utime_;
  previous_utime_ = utime;
  const double signal = Signal(deflection_rad, outlier);
  previous_signal_ = signal;
  if (!airborne) {
    Restart();  // on the ground the modes are the contact's: no test
    return state_.mismatch;
  }
  const double dt_s = previous_utime >= 0 ? (utime - previous_utime) * 1e-6 : 0.0;
  if (start_utime_ < 0 || !(std::fabs(dt_s - dt_s_) <= 0.25 * dt_s_)) {
    // A new run of samples: after lift-off, a reset, a gap or a change of
    // rate (25 % off the run's interval). The filters are designed for this
    // interval (a regular one: under 10 ms).
    ForgetRun();
    if (dt_s > 0 && dt_s < 0.01) {
      start_utime_ = utime;
      dt_s_ = dt_s;
      estimator_.Start(state_.centre_hz, options_.arm_mode_band_q, options_.arm_mode_time_constant_s, dt_s, signal);
    }
    UpdateTipMass();
    return state_.mismatch;
  }
  estimator_.Add(signal);
  // The band-pass settles (a lift-off's transient) before the sums count,
  // then they need a time constant of samples before the fit means anything.
  const double age_s = (utime - start_utime_) * 1e-6;
  const bool reading_due = age_s >= options_.arm_mode_settle_s + options_.arm_mode_time_constant_s;
  if (age_s < options_.arm_mode_settle_s) {
    estimator_.ForgetSums();
  } else if (reading_due) {
    state_.excitation = estimator_.Excitation(noise_rad_);
    Judge(utime, estimator_.FrequencyHz(excess_noise_rad_));
  }
  // Not agreed yet: waiting for the first reading, or reading the mode (a
  // mode too quiet to read is not waited for: nothing would come).
  state_.awaiting_reading = !state_.agreed && (!reading_due || std::isfinite(state_.frequency_hz));
  UpdateTipMass();
  return state_.mismatch;
}

void ArmModeMonitor::UpdateTipMass() {
  state_.learning = Learning();
  if (!state_.learning) {
    // The file's m_p is unconfirmed in the air until the readings agree:
    // before the first reading, while the mode is read, and for good on a
    // flight whose mode is too quiet to read (nothing confirms it there;
    // VALID does not wait for that, awaiting_reading does not hold).
    const bool unconfirmed = start_utime_ >= 0 && !state_.agreed;
    state_.force_tip_mass_std = unconfirmed ? options_.arm_mode_unconfirmed_tip_mass_std : 0.0;
    return;
  }
  // H0 the file's m_p, H1 the learned one (estimator/parameter_hypotheses.h):
  // the average of the two by P(H1 | readings), r = m_p / m_p_file, is
  // flown from this run's first reading on (before it H1 alone: the prior,
  // or the value and sigma resumed from the state file). Its sigma is the
  // average's once the readings' mean confirms the file's mode
  // (ReadingAgreement); before that, the learned sigma widened by how far
  // the average lies from the learned value: P(H1) starts at
  // arm_mode_tip_mass_change_probability, so a few readings near the file's
  // mode give H0 most of the weight before they could tell a 10 % heavier
  // tip from the file's.
  const double r = learner_.ratio(), r_std = learner_.ratio_std(), r_variance = r_std * r_std;
  state_.tip_mass_readings = learner_.readings();
  state_.learned_ratio = r;
  state_.learned_ratio_std = r_std;
  state_.tip_mass_change_probability = state_.tip_mass_readings > 0
                                           ? ChangedParameterProbability(r, r_std, learner_.options().prior_std,
                                                                         options_.arm_mode_tip_mass_change_probability)
                                           : 1.0;
  const HypothesesAverage ratio =
      AverageOverHypotheses(r, r_variance, r_variance, r, r_variance, state_.tip_mass_change_probability);
  const double shrunk = ratio.value - r;  // the average's distance from the learned value [1]
  // Confirmed and all but certain: the file's m_p alone, as without
  // learning once the readings confirm it (the average's residual sigma
  // would widen a matching vehicle's forces: the trirotor's rotor 1 carries
  // 4.48 N per unit r).
  const bool file_accepted = state_.file_tip_mass_agreed &&
                             state_.tip_mass_change_probability < options_.arm_mode_tip_mass_file_accepted_below;
  const double value = file_accepted ? 1.0 : ratio.value;
  const double force_std =
      file_accepted ? 0.0 : std::sqrt(state_.file_tip_mass_agreed ? ratio.variance : r_variance + shrunk * shrunk);
  // What is published and persisted with the file's m_p accepted: how far
  // the readings allow it to be off, sqrt(s^2 + (r - 1)^2).
  const double value_std = file_accepted ? std::hypot(r_std, r - 1.0) : force_std;
  state_.tip_mass_ratio = value;
  state_.tip_mass_ratio_std = value_std;
  state_.tip_mass_kg = value * learner_.map().file_tip_mass_kg();
  state_.tip_mass_std_kg = value_std * learner_.map().file_tip_mass_kg();
  // Airborne (a run of samples): that sigma in every force sigma, the
  // prior's until a reading comes, and for good on a flight whose mode is
  // too quiet to read; none once the file's m_p is accepted.
  state_.force_tip_mass_std = start_utime_ >= 0 ? force_std : 0.0;
}

void ArmModeMonitor::Judge(int64_t utime, double frequency_hz) {
  state_.frequency_hz = frequency_hz;
  // Too little of the mode above the noise: the fit sees the band-pass
  // (white noise alone reads +10 %), no judgement.
  if (!std::isfinite(frequency_hz) || state_.excitation < options_.arm_mode_min_excitation) {
    state_.frequency_hz = std::numeric_limits<double>::quiet_NaN();
    state_.relative_error = state_.statistic = 0;
    return;
  }
  state_.lowest_excitation =
      state_.lowest_excitation > 0 ? std::min(state_.lowest_excitation, state_.excitation) : state_.excitation;
  double agreement_error = 0;  // against the mode of the m_p in use, signed [1]
  if (Learning()) {
    Learn(frequency_hz, &state_.relative_error, &agreement_error);
  } else {
    const ArmModeExpectation& e = state_.expected;
    state_.relative_error = frequency_hz < e.low_hz ? frequency_hz / e.low_hz - 1.0
                                                    : (frequency_hz > e.high_hz ? frequency_hz / e.high_hz - 1.0 : 0.0);
    agreement_error = state_.relative_error;
  }
  const double error = std::fabs(state_.relative_error);
  state_.statistic = error / options_.arm_mode_limit;
  state_.peak_abs_error = std::max(state_.peak_abs_error, error);
  beyond_since_ = error > options_.arm_mode_limit ? (beyond_since_ < 0 ? utime : beyond_since_) : -1;
  const double half_limit = 0.5 * options_.arm_mode_limit;
  within_since_ = std::fabs(agreement_error) < half_limit ? (within_since_ < 0 ? utime : within_since_) : -1;
  // Agreement from the mean of every reading, not a stretch of them within
  // half the limit: tip mass +10 % reads -3 % and lies within 0.25 s
  // stretches on most flights (docs/mismatch.md).
  if (!state_.agreed) {
    agreement_.Add(agreement_error, dt_s_);
    state_.agreed = agreement_.Confirms(half_limit, options_.arm_mode_time_constant_s);
  }
  if (!state_.mismatch && beyond_since_ >= 0 && (utime - beyond_since_) * 1e-6 >= options_.arm_mode_raise_s) {
    state_.mismatch = true;
    state_.raised_utime = utime;
    ++state_.raised_count;
  } else if (state_.mismatch && within_since_ >= 0 && (utime - within_since_) * 1e-6 >= options_.arm_mode_clear_s) {
    state_.mismatch = false;
  }
}

double ArmModeMonitor::PulledError(double corrected_hz, double mode_hz) const {
  return learner_.options().band_pull * (corrected_hz / mode_hz - 1.0);
}

void ArmModeMonitor::JudgeResumedTipMass(double corrected_hz) {
  // As the file's m_p is confirmed (ReadingAgreement, half the limit): a
  // tip mass swapped since the state file was written reads its mode away
  // from the resumed one's, which the learner, sure of the resumed value,
  // would take tens of flights to follow.
  resumed_agreement_.Add(PulledError(corrected_hz, resumed_mode_hz_), dt_s_);
  const double half_limit = 0.5 * options_.arm_mode_limit;
  if (resumed_agreement_.Confirms(half_limit, options_.arm_mode_time_constant_s)) {
    resumed_mode_hz_ = 0;
  } else if (resumed_agreement_.Rejects(half_limit, options_.arm_mode_time_constant_s)) {
    learner_.Forget();
    state_.resumed_tip_mass_rejected = true;
    resumed_mode_hz_ = 0;
  }
}

void ArmModeMonitor::Learn(double frequency_hz, double* relative_error, double* agreement_error) {
  const double centre_hz = estimator_.centre_hz();
  const double corrected_hz = learner_.CorrectedHz(frequency_hz, centre_hz);
  if (resumed_mode_hz_ > 0) JudgeResumedTipMass(corrected_hz);
  // A reading barely above the noise is pulled towards the band-pass (noise
  // alone reads it): judged, but not learned from.
  if (state_.excitation >= options_.arm_mode_learn_min_excitation) {
    learner_.AddReading(frequency_hz, centre_hz, options_.arm_mode_time_constant_s, dt_s_);
  }
  *relative_error = corrected_hz < explained_low_hz_
                        ? corrected_hz / explained_low_hz_ - 1.0
                        : (corrected_hz > explained_high_hz_ ? corrected_hz / explained_high_hz_ - 1.0 : 0.0);
  const double learned_hz = learner_.LearnedHz();
  *agreement_error = corrected_hz / learned_hz - 1.0;
  // Whether the readings confirm the file's m_p as well (H0 may then take
  // over the learned one: UpdateTipMass).
  if (!state_.file_tip_mass_agreed) {
    file_agreement_.Add(PulledError(corrected_hz, file_mode_hz_), dt_s_);
    state_.file_tip_mass_agreed =
        file_agreement_.Confirms(0.5 * options_.arm_mode_limit, options_.arm_mode_time_constant_s);
  }
  // The band-pass follows the learned mode (a step of 0.5 %: re-designed
  // a few times a flight, not per sample).
  if (std::fabs(std::log(learned_hz / centre_hz)) > kRecentreStep) {
    estimator_.Recentre(learned_hz);
    state_.centre_hz = learned_hz;
  }
}

}  // namespace birotor
