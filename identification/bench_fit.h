// The stages of the bench arm fit of k, d, m_p and the gauge calibration
// (IdentifyBenchArms runs them in order; each is callable on its own by a
// test): paired strain/load-cell data, the static maps, the start from the
// statics, the arm-frequency scan, the Ceres problem, the solve with sigmas,
// the floors and the result.
#pragma once

#include <ceres/problem.h>

#include <array>
#include <deque>
#include <vector>

#include "identification/clamped_arm_residual.h"
#include "identification/identification_options.h"
#include "identification/identification_result.h"
#include "samples/rotor_count.h"
#include "samples/sensor_log.h"

namespace birotor {

// Global parameters of the clamped-arm fit, each a one-scalar Ceres block.
enum BenchArmParameter : int {
  kBenchK = 0,        // k / k_scale
  kBenchD = 1,        // d / d_scale
  kBenchTipMass = 2,  // m_p / m_scale
  kBenchScale1 = 3,   // gauge scale arm 1 [1]
  kBenchScale2 = 4,   // gauge scale arm 2 [1]
  kBenchOffset1 = 5,  // gauge offset arm 1 / sigma_b
  kBenchOffset2 = 6,  // gauge offset arm 2 / sigma_b
};
constexpr int kBenchArmParameters = 7;
using BenchTheta = std::array<double, kBenchArmParameters>;

// Paired strain/load-cell samples of one arm of one log.
struct ArmData {
  int arm = 0;
  std::vector<int64_t> utime;
  std::vector<double> deflection_rad, force_n;
  std::vector<bool> valid;
};

// Data stage: strain samples of every (log, arm) with the load-cell force at
// the same time; the valid pairs also go to map_b, map_f (the static map's data).
std::vector<ArmData> CollectArmData(const std::vector<SensorLog>& logs, std::vector<double> map_b[kBirotorRotors],
                                    std::vector<double> map_f[kBirotorRotors]);

// One output-error window [begin, end) of data[data_index].
struct ArmWindow {
  size_t data_index, begin, end;
};

// Windows of bench_arm_window_s over every (log, arm) run of valid pairs.
std::vector<ArmWindow> ArmWindows(const std::vector<ArmData>& data, const IdentificationOptions& options);
std::vector<ClampedArmWindowResidual::Sample> ArmWindowSamples(const std::vector<ArmData>& data, const ArmWindow& w);

// Static line reading = a + c f of one arm by least squares (gauges.md:
// a = o_i - s_i sign_i L m_p g / k, c = s_i sign_i L / k).
struct StaticLine {
  double intercept_rad = 0.0;  // a
  double slope_rad_n = 0.0;    // c [rad/N]
};
StaticLine FitStaticLine(const std::vector<double>& force_n, const std::vector<double>& reading_rad);

// Map stage: the deflection-force map of each arm (map_degree) into
// result->maps, with its fit and residual panels into result->plots.
void FitBenchMaps(const std::vector<double> map_b[kBirotorRotors], const std::vector<double> map_f[kBirotorRotors],
                  const IdentificationOptions& options, IdentificationResult* result);

// Guess stage: the start from the statics. k from the static slopes with
// the base gauge scales (per arm c = s sign L / k), m_p the weighed one or
// the base file's, the offsets from the intercepts a = o - c m_p g.
struct BenchStatics {
  StaticLine lines[kBirotorRotors];
  ClampedArmWindowResidual::Scales scales{};
  double stiffness_n_m_rad = 0.0;  // k0
  double tip_mass_kg = 0.0;        // m_p0
};
BenchStatics BenchArmStatics(const std::vector<double> map_b[kBirotorRotors],
                             const std::vector<double> map_f[kBirotorRotors], const BirotorParams& base,
                             const CalibrationFact& fact);
// theta at (k, m_p, gauge scales) holding the static lines; d at the base value.
BenchTheta BenchThetaAt(const BenchStatics& statics, const BirotorParams& base, double strain_noise_rad,
                        double stiffness_n_m_rad, double tip_mass_kg, const double gauge_scale[kBirotorRotors]);

// Sum of squared whitened residuals of the windows at theta with each
// window's initial state chosen by linear least squares (the output is
// linear in (b_0, b_dot_0) up to the tiny cos(b) term).
double CostWithBestInitialStates(const std::vector<ClampedArmWindowResidual*>& windows, const double* theta);

// Scan stage: the arm frequency k / m_p over a factor 4 in 3 % steps on up
// to 24 windows, holding the static slope s_i / k (the output-error cost has
// local minima a few percent apart in frequency). Scale held: m_p moves;
// tip mass weighed and scales free: k and s_i move together. The best theta.
BenchTheta ScanArmFrequency(const std::vector<ArmData>& data, const std::vector<ArmWindow>& windows,
                            const BenchStatics& statics, const BirotorParams& base,
                            const IdentificationOptions& options);

// Build stage: one clamped-arm window residual per window over theta, each
// window's state starting at rest on the static line; m_p held or under its
// weighed prior, the scales held or under the factory prior (options.calibration).
struct BenchArmProblem {
  ceres::Problem problem;
  BenchTheta theta{};
  std::deque<std::array<double, 2>> states;
  std::vector<ceres::ResidualBlockId> blocks;
};
void BuildBenchArmProblem(const std::vector<ArmData>& data, const std::vector<ArmWindow>& windows,
                          const BenchStatics& statics, const BirotorParams& base, const IdentificationOptions& options,
                          BenchArmProblem* fit);

}  // namespace birotor
