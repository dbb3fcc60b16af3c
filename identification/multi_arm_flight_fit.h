// Flight identification of a vehicle with N elastic arms (no load cells):
// per rotor tau_m,i from its ESC telemetry (the birotor's motor fit on that
// rotor alone), then per arm k_i and per rotor c_T,i from the free-flight
// output error of multi_arm_flight_residual.h over windows of the gauges,
// the pitch rate and the specific force, with the birotor flight fit's
// honesty rules (sigma from the information matrix inflated by the residual
// scale and correlation, at least the window sandwich; determined only when
// sigma <= max_relative_sigma). Each stage is a function a test can call.
#pragma once

#include <ceres/problem.h>

#include <array>
#include <deque>
#include <string>
#include <vector>

#include "identification/flight_fit.h"
#include "identification/identification_options.h"
#include "identification/multi_arm_bench_fit.h"
#include "identification/multi_arm_flight_residual.h"

namespace birotor {

// Data stage: per log the strain times and the window samples (gauges
// through the description's calibration b = (b_meas - o_i) / s_i, rotor
// speeds of the motor model driven by the recorded commands with each
// rotor's tau_m, IMU when options.use_imu), and every candidate window.
struct MultiArmFlightSamples {
  std::vector<std::vector<int64_t>> utime;                                 // per log [us]
  std::vector<std::vector<MultiArmFlightWindowResidual::Sample>> samples;  // per log
  std::vector<FlightWindow> candidates;                                    // every valid window
  bool any_imu = false;
};
MultiArmFlightSamples CollectMultiArmFlightSamples(const std::vector<MultiArmBenchLog>& logs,
                                                   const VehicleDescription& motors,
                                                   const IdentificationOptions& options);

// Guess stage: a window's initial state, the measured pitch rate (0 without
// IMU) and deflections, the deflection rates from a least-squares line
// through the first five samples.
FlightState<double> InitialMultiArmWindowState(const std::vector<MultiArmFlightWindowResidual::Sample>& samples,
                                               int arm_count);

// The Ceres problem of the windows: one k, one c_T and one m_p ratio block
// per arm (value = ratio * the description's; m_p held unless
// options.flight_fit_tip_mass), one initial state per window.
struct MultiArmFlightProblem {
  ceres::Problem problem;
  std::array<double, kMaxArms> stiffness_ratio{1, 1, 1, 1, 1, 1};
  std::array<double, kMaxArms> thrust_ratio{1, 1, 1, 1, 1, 1};
  std::array<double, kMaxArms> tip_mass_ratio{1, 1, 1, 1, 1, 1};
  std::deque<std::vector<double>> states;       // per window x_0
  std::vector<ceres::ResidualBlockId> windows;  // one per window
  int arm_count = 0;
  bool fit_tip_mass = false;
  // The k blocks, then the c_T and the m_p blocks.
  std::vector<double*> Blocks() {
    std::vector<double*> blocks;
    for (std::array<double, kMaxArms>* ratio : {&stiffness_ratio, &thrust_ratio, &tip_mass_ratio}) {
      for (int i = 0; i < arm_count; ++i) blocks.push_back(&(*ratio)[static_cast<size_t>(i)]);
    }
    return blocks;
  }
};

// Build stage over the chosen windows of data, against `base`.
void BuildMultiArmFlightProblem(const MultiArmFlightSamples& data, const std::vector<FlightWindow>& windows,
                                const VehicleDescription& base, const IdentificationOptions& options,
                                MultiArmFlightProblem* fit);

// Solve stage: with every m_p held first, then (fit_tip_mass) with m_p free
// from that optimum. From the description's k and c_T with m_p free the
// solver fell into a far minimum (flight_id of the modified trirotor: c_T
// +53 %, k +12 %), as the birotor's flight fit did (flight_fit.h CheckTipMass).
void SolveMultiArmFlightProblem(const IdentificationOptions& options, MultiArmFlightProblem* fit);

// Sigma stage: the residual statistics of every channel (gauges, gyro,
// accelerometer x, z), the largest inflation (VarianceInflation) and the
// sigmas of the ratio blocks (SharedSigmas with the windows as clusters);
// each gauge's whitened RMS into *strain_rms_whitened.
std::vector<BlockSigma> MultiArmFlightSigmas(const IdentificationOptions& options, bool any_imu,
                                             MultiArmFlightProblem* fit, std::vector<double>* strain_rms_whitened);

// The whole flight fit. Every log must match `base` (MultiArmLogMismatch);
// tau_m,i comes first (it drives the motor model), then k_i, c_T,i and
// m_p,i when options.flight_fit_tip_mass and the description has no rotor
// turbulence (the birotor's rule judges m_p only with the turbulence
// modelled, which this fit does not do). m_p,i is determined when its sigma is
// at most max_relative_sigma, and replaces the description's only when it
// lies more than consistency_sigmas from it (the birotor's rule: a flight
// that agrees with the base file does not replace it). d_i and o_i are held
// and reported NOT DETERMINED with the advice (result.advice): the windows
// barely see d; o_i and k_i are nearly one direction at the nearly constant
// thrust of a flight (fitted together on flight_id, 60 s: k's sigma 3.6-9 %
// instead of 0.7-1.3 %, o_i's 8e-5 rad and more), while an o_i wrong by
// 2e-5 rad moves k by about 1 %: the gauges need a tare at power-up.
// result.ok: every k_i, c_T,i, tau_m,i determined.
MultiArmIdentificationResult IdentifyMultiArmFlight(const std::vector<MultiArmBenchLog>& logs,
                                                    const VehicleDescription& base,
                                                    const IdentificationOptions& options);

}  // namespace birotor
