// What an identification run produced: the identified vehicle parameters with
// one-sigma uncertainties, residual statistics per residual block, the static
// deflection-force maps, and the reasons when the data could not give numbers.
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "identification/identification_options.h"
#include "identification/sample_cleaning.h"
#include "model/birotor_params.h"
#include "samples/rotor_count.h"

namespace birotor {

// How an estimate was obtained, or why it was kept at the base value. The
// library gives the kind and the numbers; the words are the presentation's
// (params/identified_parameter_file.h NoteText, the report's notes).
enum class EstimateBasis {
  kNone,                   // no fit gave it (the fit was refused before)
  kClampedArmFit,          // bench: output error of the clamped arm over `windows` windows
  kThrustPairs,            // bench: `windows` load-cell/telemetry pairs `spacing_s` apart
  kMotorFit,               // tau_m: output error over `windows` windows with `command_steps` steps
                           // (at least min_command_steps on a motor)
  kMotorFitContinuous,     // tau_m: the same fit with fewer steps, excited by the commands' continuous
                           // variation (its relative sigma `relative_sigma` within max_relative_sigma)
  kMotorNotExcited,        // tau_m: `command_steps` per motor above `step_threshold_rad_s` (an error too)
  kFreeArmFit,             // flight: `windows` of `candidate_windows` windows, `with_imu`; `joint`: with
                           // `load_cell_pairs` pairs and `clamped_windows` bench windows in one problem
  kTipMassAgreesWithBase,  // flight m_p: `value` +- `sigma` [kg] is `distance_sigmas` from the base (kept)
  kTipMassHeld,            // flight m_p held: `relative_sigma` at the held fit, `data_share` from the data
  kDampingNotFitted,       // flight d: flight_fit_damping is off, base value kept
};

// What was added to an estimate after its fit, in the order it was added.
enum class EstimateRemark {
  kDampingFloor,               // sigma includes bench_damping_floor
  kFrequencyFloor,             // sigma includes bench_frequency_floor
  kGaugeScaleFloor,            // flight: sigma includes --gauge-scale-std
  kTipMassFloorThroughOffset,  // bench o_i: sigma includes m_p's frequency floor through the static intercept
  kWidenedForMisfit,           // bench: sigma widened for the clamped-arm misfit (WarningKind::kArmModelMisfit)
  kTipMassDataShare,           // flight m_p: `data_share` of its information from the data
  kRelativeToGaugeScale,       // flight k, m_p: relative to the base file's gauge_scale (no --gauge-scale-std)
  kBenchLogsAlone,             // joint fit s_i, o_i: the bench logs' own fit, held in the joint fit
};

struct EstimateNote {
  EstimateBasis basis = EstimateBasis::kNone;
  int windows = 0;                             // fitted windows (kThrustPairs: pairs)
  int candidate_windows = 0;                   // kFreeArmFit: windows the logs offered
  bool with_imu = false;                       // kFreeArmFit
  bool joint = false;                          // kFreeArmFit: the joint bench + flight problem ...
  int load_cell_pairs = 0;                     // ... with this many thrust pairs ...
  int clamped_windows = 0;                     // ... and clamped-arm windows
  int command_steps[kBirotorRotors] = {0, 0};  // kMotorFit, kMotorNotExcited: per motor
  double step_threshold_rad_s = std::numeric_limits<double>::quiet_NaN();  // kMotorNotExcited
  double spacing_s = std::numeric_limits<double>::quiet_NaN();             // kThrustPairs [s]
  double value = std::numeric_limits<double>::quiet_NaN();                 // kTipMassAgreesWithBase [kg]
  double sigma = std::numeric_limits<double>::quiet_NaN();                 // kTipMassAgreesWithBase [kg]
  double distance_sigmas = std::numeric_limits<double>::quiet_NaN();       // kTipMassAgreesWithBase
  double relative_sigma = std::numeric_limits<double>::quiet_NaN();        // kTipMassHeld, kMotorFitContinuous [1]
  double data_share = std::numeric_limits<double>::quiet_NaN();            // kTipMassHeld, kTipMassDataShare [1]
  // The size the sigma was judged against when it is not |value| (bench o_i,
  // which may be zero: the strain noise) [unit of the value]; NaN: |value|.
  double judged_size = std::numeric_limits<double>::quiet_NaN();
  std::vector<EstimateRemark> remarks;
};

// The refusal of tau_m for want of excitation (an error line of the result,
// and the words of EstimateBasis::kMotorNotExcited).
std::string MotorNotExcitedError(const EstimateNote& note);

// One identified scalar.
struct ParameterEstimate {
  std::string key;     // YAML key of the `vehicle:` section, e.g. "arm_stiffness_n_m_rad"
  std::string symbol;  // k, d, c_T, tau_m
  double value = std::numeric_limits<double>::quiet_NaN();  // SI, unit in the key
  double sigma = std::numeric_limits<double>::quiet_NaN();  // one sigma, same unit
  bool determined = false;                                  // false: the data could not determine it; base value kept
  EstimateNote note;                                        // how sigma was obtained, or why not determined

  static ParameterEstimate Named(std::string key_name, std::string symbol_name) {
    ParameterEstimate e;
    e.key = std::move(key_name);
    e.symbol = std::move(symbol_name);
    return e;
  }
};

// Which residuals a ResidualSummary is about (words and unit:
// params/identified_parameter_file.h ResidualBlockText, ResidualBlockUnit).
enum class ResidualBlock {
  kMotorTelemetry,      // omega_meas - first-order model [rad/s]
  kLoadCell,            // bench: force - c_T omega^2 [N]
  kClampedArm,          // bench: strain of the clamped arm model [rad]
  kFreeFlightStrain1,   // flight: strain arm 1, free-flight model [rad]
  kFreeFlightStrain2,   // flight: strain arm 2 [rad]
  kGyroPitchRate,       // flight: IMU pitch rate [rad/s]
  kAccelerometerX,      // flight: specific force x [m/s^2]
  kAccelerometerZ,      // flight: specific force z [m/s^2]
  kLoadCellJointFit,    // joint bench + flight fit: the bench's load cells [N]
  kClampedArmJointFit,  // joint bench + flight fit: the bench's clamped arms [rad]
};

// Residuals of one kind of block after the fit (without the robust loss).
struct ResidualSummary {
  ResidualBlock block = ResidualBlock::kMotorTelemetry;
  int count = 0;                    // scalar residuals
  double rms_whitened = 0.0;        // [sigma]
  double rms_si = 0.0;              // [unit of the block]
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

// One parameter's share of the information of each log (1 / sigma^2 of that
// log alone over the sum; 0 where the log alone does not determine it).
struct LogShares {
  std::string symbol;
  std::vector<std::string> logs;  // each log's source
  std::vector<double> shares;     // [1], one per log
};

struct IdentificationResult {
  bool ok = false;                              // false: `errors` says what is missing; no numbers
  std::string mode;                             // "bench", "flight" or "bench+flight"
  std::vector<std::string> errors;              // what the data lacks, one line each
  std::vector<IdentificationWarning> warnings;  // e.g. parameter kept at its base value
  BirotorParams params;                         // base parameters with the identified values
  std::vector<ParameterEstimate> estimates;
  std::vector<ResidualSummary> residuals;
  std::vector<DeflectionForceMap> maps;
  std::vector<std::string> sources;  // logs used
  // The calibration fact used (bench: factory gauge scale or weighed tip
  // mass; words: params/identified_parameter_file.h CalibrationFactText).
  bool has_calibration_fact = false;
  CalibrationFact calibration_fact;
  double factory_gauge_scale[kBirotorRotors] = {1.0,
                                                1.0};  // the base file's gauge_scale, the factory fact when not weighed
  // Parameters the data cannot separate, with the combination that is
  // determined (from the correlation of the fitted parameters, or named by
  // the fit that held one of them).
  std::vector<DeterminedCombination> correlations;
  // Several logs: per parameter, each log's share of the information
  // (1 / sigma^2 of that log alone; words: LogSharesText).
  std::vector<LogShares> log_shares;
  // Joint bench + flight fit: the bench logs' own fit (the flight logs' base
  // in the per-log comparison).
  BirotorParams bench_params;
  std::vector<FitPlot> plots;    // fit versus data, a few panels
  SampleCleaningReport dropped;  // bad samples dropped before fitting, all logs
};

}  // namespace birotor
