// What an identification run produced: the identified vehicle parameters with
// one-sigma uncertainties, residual statistics per residual block, the static
// deflection-force maps, and the reasons when the data could not give numbers.
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "identification/sample_cleaning.h"
#include "model/vehicle_params.h"

namespace birotor {

// One identified scalar.
struct ParameterEstimate {
  std::string key;     // YAML key of the `vehicle:` section, e.g. "arm_stiffness_n_m_rad"
  std::string symbol;  // k, d, c_T, tau_m
  double value = std::numeric_limits<double>::quiet_NaN();  // SI, unit in the key
  double sigma = std::numeric_limits<double>::quiet_NaN();  // one sigma, same unit
  bool determined = false;                                  // false: the data could not determine it; base value kept
  std::string note;                                         // why not determined, or how sigma was obtained

  static ParameterEstimate Named(std::string key_name, std::string symbol_name) {
    ParameterEstimate e;
    e.key = std::move(key_name);
    e.symbol = std::move(symbol_name);
    return e;
  }
};

// Residuals of one kind of block after the fit (without the robust loss).
struct ResidualSummary {
  std::string name;                 // e.g. "motor telemetry"
  std::string unit;                 // unit of rms_si
  int count = 0;                    // scalar residuals
  double rms_whitened = 0.0;        // [sigma]
  double rms_si = 0.0;              // [unit]
  double variance_inflation = 1.0;  // factor applied to the covariance (chi2/dof, correlation)
};

// Static map force_n = sum_j coeff[j] deflection_rad^j of one arm (bench).
struct DeflectionForceMap {
  int arm = 0;                       // 0: arm 1, 1: arm 2
  std::vector<double> coefficients;  // [N / rad^j]
  std::vector<double> sigmas;        // one sigma of each coefficient
  double residual_rms_n = 0.0;       // RMS of force - map(deflection) [N]
  double deflection_min_rad = 0.0;   // range of the data [rad]
  double deflection_max_rad = 0.0;
  int samples = 0;
};

// What a panel of fit versus data shows (its title and axes are written by
// plot/fit_plot.cc, not here).
enum class FitPanel {
  kMotorResponse,     // x: time in window [s]; telemetry vs first-order model [rad/s]; value: tau_m [s]
  kThrustMap,         // x: telemetry speed [rad/s]; load cell vs c_T omega^2 [N]
  kArmMap,            // x: deflection of `arm` [mrad]; load-cell force vs map [N]; value: map degree
  kArmMapResidual,    // x: deflection of `arm` [mrad]; force - map [N]; value: residual RMS [N]
  kFlightDeflection,  // x: time in window [s]; deflection of `arm` [mrad]; window of windows
};

// One panel of fit versus data for the --plot figure: measured points and
// the fitted model at the same abscissae.
struct FitPlot {
  FitPanel panel = FitPanel::kMotorResponse;
  int arm = 0;         // 0: arm 1, 1: arm 2 (arm panels)
  int window = 0;      // kFlightDeflection: window index (0-based) ...
  int windows = 0;     // ... of this many
  double value = 0.0;  // see FitPanel
  std::vector<double> x;
  std::vector<double> data;   // measured
  std::vector<double> model;  // fitted model (NaN where there is none)
};

// What a warning is about. The library gives the kind and the numbers; the
// words are the presentation's (params/identified_parameter_file.h
// WarningText, used by the report, the file header and the tool).
enum class WarningKind {
  kArmModelMisfit,         // bench: strain residual RMS `value` [sigma] above misfit_rms_warn; arm sigmas widened by it
  kNotExcitedOnBench,      // bench: `symbol` (d or m_p) not determined, the arm modes barely excited; base value kept
  kNotDeterminedInFlight,  // flight: `symbol` not determined by the flight data; base value kept
  kTipMassHeldInFlight,    // flight: m_p held by the determinability check (issue 26); base value kept
  kTipMassAgreesWithBase,  // flight: m_p `value` +- `sigma` [kg] is `distance_sigmas` from the base value (kept)
};

// What would determine a parameter that this log does not (issue 26 item 2).
enum class ExcitationAdvice {
  kNone,
  // m_p: 30 s of 0.4 m steps, horizontal and vertical (birotor-sim
  // --scenario mass_id: m_p sigma 0.7 %), a weighed tip mass with a bench
  // log, or a bench identification (0.1 %).
  kTipMassSteps,
};

struct IdentificationWarning {
  WarningKind kind = WarningKind::kNotDeterminedInFlight;
  std::string symbol;  // the parameter (k, d, c_T, m_p; empty for kArmModelMisfit)
  ExcitationAdvice advice = ExcitationAdvice::kNone;
  double value = std::numeric_limits<double>::quiet_NaN();            // see WarningKind
  double sigma = std::numeric_limits<double>::quiet_NaN();            // one sigma of `value`
  double distance_sigmas = std::numeric_limits<double>::quiet_NaN();  // |value - base| / sigma
};

// Two parameters the data cannot separate and the combination of them that
// is determined (words: params/identified_parameter_file.h CombinationText).
enum class CombinationKind {
  kRatio,                // a / b (correlation above the threshold)
  kProduct,              // a b (correlation below minus the threshold)
  kThrustOverTotalMass,  // flight with m_p held: c_T / (m + 2 m_p) (the accelerometer sees thrust over mass)
};
struct DeterminedCombination {
  CombinationKind kind = CombinationKind::kRatio;
  std::string a, b;                                                  // the symbols, e.g. k and s_1; c_T and m_p
  double correlation = std::numeric_limits<double>::quiet_NaN();     // of a and b (kRatio, kProduct) [1]
  double relative_sigma = std::numeric_limits<double>::quiet_NaN();  // of the combination, one sigma [1]
  double held_value = std::numeric_limits<double>::quiet_NaN();      // kThrustOverTotalMass: b held at this [kg]
};

struct IdentificationResult {
  bool ok = false;                              // false: `errors` says what is missing; no numbers
  std::string mode;                             // "bench", "flight" or "bench+flight"
  std::vector<std::string> errors;              // what the data lacks, one line each
  std::vector<IdentificationWarning> warnings;  // e.g. parameter kept at its base value
  VehicleParams params;                         // base parameters with the identified values
  std::vector<ParameterEstimate> estimates;
  std::vector<ResidualSummary> residuals;
  std::vector<DeflectionForceMap> maps;
  std::vector<std::string> sources;  // logs used
  // The calibration fact used (bench: factory gauge scale or weighed tip mass).
  std::string calibration_fact;
  // Parameters the data cannot separate, with the combination that is
  // determined (from the correlation of the fitted parameters, or named by
  // the fit that held one of them).
  std::vector<DeterminedCombination> correlations;
  // Several logs: per parameter, each log's share of the information
  // (1 / sigma^2 of that log alone), e.g. "k: a.lcm 70.0 %, b.lcm 30.0 %".
  std::vector<std::string> log_shares;
  // Joint bench + flight fit: the bench logs' own fit (the flight logs' base
  // in the per-log comparison).
  VehicleParams bench_params;
  std::vector<FitPlot> plots;    // fit versus data, a few panels
  SampleCleaningReport dropped;  // bad samples dropped before fitting, all logs
};

}  // namespace birotor
