// The stages of the free-flight fit of k, d, c_T, m_p (IdentifyFlightArms
// runs them in order; each is callable on its own by a test): the samples
// and candidate windows of the logs, the scan that picks the windows, the
// Ceres problem with each window's initial guess, the solve, the sigmas and
// the result.
#pragma once

#include <ceres/problem.h>

#include <algorithm>
#include <array>
#include <deque>
#include <memory>
#include <vector>

#include "identification/bench_residuals.h"
#include "identification/fit_support.h"
#include "identification/free_arm_residual.h"
#include "identification/identification_options.h"
#include "identification/identification_result.h"
#include "samples/sensor_log.h"

namespace birotor {

// One window [begin, end) of strain samples of log `log`.
struct FlightWindow {
  size_t log = 0, begin = 0, end = 0;
};

// Data stage: per log, the strain times and the model samples (deflections
// through the base file's gauge calibration, model rotor speeds from the
// commands and `motor`'s tau_m, IMU), and every candidate window.
struct FlightSamples {
  std::vector<std::vector<int64_t>> utime;                          // per log [us]
  std::vector<std::vector<FreeArmWindowResidual::Sample>> samples;  // per log
  std::vector<FlightWindow> candidates;                             // every valid window
  bool any_imu = false;
};
FlightSamples CollectFlightSamples(const std::vector<SensorLog>& logs, const BirotorParams& base,
                                   const BirotorParams& motor, const IdentificationOptions& options);

// Scan stage: at most max_windows of the candidates, spread evenly (0: all).
// The arm modes ring after every manoeuvre, so a subset carries nearly all
// the information at a fraction of the cost.
std::vector<FlightWindow> SelectFlightWindows(const std::vector<FlightWindow>& candidates, int max_windows);

// Guess stage: a window's initial state, the measured pitch rate and
// deflections and the deflection rates from a least-squares line through
// the first five samples (strain noise 2e-5 rad gives a few mrad/s).
std::array<double, kFreeArmStateSize> InitialWindowState(const std::vector<FreeArmWindowResidual::Sample>& samples);

// The shared ratio blocks of the flight problem (value = ratio * scale).
enum FlightParameter : int { kFlightK = 0, kFlightD = 1, kFlightThrust = 2, kFlightTipMass = 3 };
constexpr int kFlightParameters = 4;

// The Ceres problem of the flight windows (and, in a joint fit, the bench's
// residuals); storage that must not move once added.
struct FlightProblem {
  ceres::Problem problem;
  FreeArmWindowResidual::Scales scales{};
  std::array<double, kFlightParameters> ratio = {1.0, 1.0, 1.0, 1.0};
  std::deque<std::array<double, kFreeArmStateSize>> states;  // per window x_0
  std::deque<std::vector<double>> knots;                     // per window [eta_1 knots, eta_2 knots]
  std::vector<ceres::ResidualBlockId> windows;               // one per flight window
  std::vector<const FreeArmWindowResidual*> functors;        // owned by the problem
  std::vector<ceres::ResidualBlockId> priors;                // per window: its knots' turbulence prior
  double turbulence_std = 0.0;                               // of the priors (base file) [1]
  double turbulence_corr_time_s = 0.0;
  // The same windows and priors without the Huber weighting, over the same
  // blocks (flight-only fits with turbulence knots; null otherwise): the
  // start of SolveFlightProblem.
  std::unique_ptr<ceres::Problem> start;
  BenchResiduals bench;  // joint fit only
  bool joint = false;
  bool model_turbulence = false;
  std::vector<double*> Blocks() { return {&ratio[0], &ratio[1], &ratio[2], &ratio[3]}; }
};

// Build stage: one residual block per window over the shared ratios (scaled
// by `base`), its initial state and turbulence knots under their prior; the
// bench residuals when bench_logs is not null. d (and m_p) held as the
// options say, unless the fit is joint.
void BuildFlightProblem(const FlightSamples& data, const std::vector<FlightWindow>& windows, const BirotorParams& base,
                        const IdentificationOptions& options, const std::vector<SensorLog>* bench_logs,
                        FlightProblem* fit);

// Solve stage: the start problem (no Huber weighting; tolerance 1e-3), or
// in a joint fit the knots held at 0 first (1e-3), then the problem (1e-6).
// `fraction`: share of the whole fit done before it (progress).
void SolveFlightProblem(const IdentificationOptions& options, FlightProblem* fit, double fraction = 0.0);

// Solve stage after a change of what is held: one solve from the current
// values at the final tolerance.
void ResolveFlightProblem(const IdentificationOptions& options, FlightProblem* fit, double fraction = 0.0);

// Determinability stage (issue 26): the relative one sigma of a ratio block
// from the information matrix with every other parameter marginalised (the
// window states and turbulence knots included; the block made free for the
// computation, its constancy restored after), once under the turbulence
// prior of the base file and once under that prior widened by `widen` in
// standard deviation. Information that the recorded excitation gives stays
// when the prior is widened; information that only the assumed turbulence
// statistics give (a hover: the controller's reaction to the turbulence is
// the only excitation of the pitch inertia) shrinks with it. Infinity along
// a singular direction.
struct PriorSensitivity {
  double relative_sigma = 0.0;          // under the base file's turbulence prior [1]
  double relative_sigma_widened = 0.0;  // under the widened prior [1]
};
PriorSensitivity RatioPriorSensitivity(const IdentificationOptions& options, int block, double widen,
                                       FlightProblem* fit);

// The share of a block's information that the recorded data give, from the
// sigmas under the base and the widened turbulence prior: with information
// D (data) + P (prior, scaling as 1 / widen^2), r = sigma_widened / sigma,
//   share = D / (D + P) = (1 / r^2 - 1 / widen^2) / (1 - 1 / widen^2), in [0, 1].
double DataInformationShare(const PriorSensitivity& s, double widen);

// The turbulence prior's widening used for the determinability (x4 in
// standard deviation: a prior-borne share shrinks 16-fold).
constexpr double kPriorWidening = 4.0;

// Solve and determinability stages of m_p in a flight-only fit with
// flight_fit_tip_mass and the turbulence modelled: solved with m_p held at
// the base value, then m_p judged at that optimum: determined when its
// relative sigma (information, every other parameter marginalised) is at
// most max_relative_sigma and at least flight_min_data_share of its
// information comes from the data. `free`: m_p left free for a further
// solve (otherwise held at the base value). Other fits: solved as built.
struct TipMassCheck {
  bool applies = false;         // the check ran
  bool free = false;            // m_p is free in the problem now
  double relative_sigma = 0.0;  // at the held optimum, not inflated [1]
  double data_share = 0.0;      // DataInformationShare [1]
  // Set by IdentifyFlightArms after the solve with m_p free: the flight's
  // value and sigma, its distance from the base value [sigma], and whether
  // that is within options.consistency_sigmas (then m_p keeps the base
  // value: a flight that agrees with the base file does not replace it).
  double flight_value_kg = 0.0;
  double flight_sigma_kg = 0.0;
  double sigmas_from_base = 0.0;
  bool agrees_with_base = false;
};
TipMassCheck CheckTipMass(const IdentificationOptions& options, FlightProblem* fit);

// Sigma stage: residual summaries per channel (appended to *residuals), the
// inflation from their autocorrelation, and the sigmas of the four ratios
// (inflated information matrix, at least the window sandwich).
std::vector<BlockSigma> FlightSigmas(const IdentificationOptions& options, bool any_imu,
                                     const std::vector<SensorLog>* bench_logs, FlightProblem* fit,
                                     std::vector<ResidualSummary>* residuals);

// Result stage: the estimates of k, d, c_T (and m_p) with their notes, the
// floors (bench floors in a joint fit, --gauge-scale-std otherwise), the
// warnings and advice, into *result (params by StoreEstimates).
void StoreFlightResult(const FlightProblem& fit, const FlightSamples& data, const std::vector<BlockSigma>& sigma,
                       const TipMassCheck& tip_check, const BirotorParams& base, const IdentificationOptions& options,
                       IdentificationResult* result);

// Plot data: measured and predicted deflections of both arms over two
// windows, at one third and two thirds of them.
std::vector<FitPlot> FlightPlots(const FlightProblem& fit);

}  // namespace birotor
