#pragma once

// What a learned strain scale is (learn_strain_scale; docs/mismatch.md,
// "What a learned strain scale is"). The EKF learns per arm
//   g_i = (s_i / s_i,file) (k_file / k_i) (M / M_file),
// the gauge's reading per newton of rotor force against the file's: a gauge
// scale s_i, the arm's stiffness k_i and a payload (the accelerometer weighs
// the total force against the file's mass M_file, so a heavier vehicle reads
// as gauges that read high) are one number to it. The arm mode tells them
// apart: its frequency f scales with sqrt(k) (every spring of the
// linearised vehicle is an arm hinge) and falls with the tip mass m_p, and
// neither a gauge's scale nor a payload on the body's centre moves it much.
// The arm-mode learner reads f as a tip mass r = m_p / m_p,file with the
// file's stiffness (estimator/tip_mass_learning.h); its log-frequency shift
// b = ln f(r) - ln f(1) is the evidence used here.
//
// Evidence y = (a, d, b) [1]: a = (ln g_1 + ln g_2) / 2, d = ln g_1 - ln g_2,
// b as above. Single-change hypotheses, each y = A theta + noise with
// theta ~ N(0, prior^2):
//   kNone        the file (theta none)
//   kStiffness   both arms' stiffness k = k_file e^kappa: a = -kappa, b = kappa / 2
//   kTipMass     both tip masses m_p = m_p,file e^mu: b = S mu (S = d ln f / d ln m_p)
//   kGauge1/2    one gauge's scale s = s_file e^sigma: a = sigma / 2, d = +-sigma
//   kCommonScale a payload M = M_file e^beta, or both gauges alike: a = beta
// with the measurement covariance of g's and the mode's learned sigmas plus
// a model tolerance on each component (the hover linearisation against the
// flight). The posterior weight of each is its prior probability times the
// marginal likelihood N(y; 0, A A^T prior^2 + R); the data are explained
// when the best hypothesis's Mahalanobis distance is within a chi-square
// limit. No allocation.

#include <array>

namespace birotor {

enum class ScaleChange { kNone, kStiffness, kTipMass, kGauge1, kGauge2, kCommonScale };
constexpr int kScaleChangeCount = 6;

struct ScaleEvidence {
  double log_scale[2] = {0.0, 0.0};      // ln g_i [1]
  double log_scale_var[2] = {0.0, 0.0};  // var ln g_i [1]
  double mode_shift = 0.0;               // b = ln f(r) - ln f(1) [1]
  double mode_shift_var = 0.0;           // its variance [1]
};

struct ScaleAttributionOptions {
  double stiffness_prior_std = 0.2;      // ln k / k_file [1]
  double tip_mass_prior_std = 0.15;      // ln m_p / m_p,file [1]
  double gauge_scale_prior_std = 0.2;    // ln s / s_file, one gauge [1]
  double common_scale_prior_std = 0.15;  // ln M / M_file, or both gauges alike [1]
  double change_probability = 0.1;       // prior of each change; the file's is the rest [1]
  double tolerance = 0.02;               // model tolerance on a, d and b (one sigma) [1]
  double tip_mass_mode_slope = -0.5;     // S = d ln f / d ln m_p at the file's m_p [1]
  double explained_distance2 = 16.3;     // chi-square limit of the best hypothesis (3 dof, 0.999) [1]
};

struct ScaleAttribution {
  std::array<double, kScaleChangeCount> weight{};  // posterior of each ScaleChange, summing to 1 [1]
  double best_distance2 = 0.0;                     // smallest y^T C^-1 y over the hypotheses [1]
  bool explained = true;                           // best_distance2 within explained_distance2

  double of(ScaleChange change) const { return weight[static_cast<size_t>(change)]; }
};

ScaleAttribution AttributeScales(const ScaleEvidence& evidence, const ScaleAttributionOptions& options);

}  // namespace birotor
