// Options of the identification (noise levels used to whiten the residuals,
// window lengths, robust loss, acceptance thresholds). Every field has a
// documented default; params/identification_options_yaml.h loads the
// `identification:` section.
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <string>

namespace birotor {

// The one fact that bench statics and dynamics cannot give (shared/spec/gauges.md:
// they fix s_i / k, k / m_p and the offsets; one of s_i, k, m_p must come from
// elsewhere). From the command line (birotor-identify --tip-mass-kg,
// --tip-mass-std-kg, --gauge-scale-std), not from the options file.
struct CalibrationFact {
  // Weighed tip mass m_p [kg]; NaN: not weighed, then the gauge scales are
  // taken as the base file's gauge_scale (the factory scale, 1 for an ideal
  // gauge) and m_p is identified.
  double tip_mass_kg = std::numeric_limits<double>::quiet_NaN();
  // One sigma of the weighed tip mass [kg]; 0 holds m_p at tip_mass_kg.
  double tip_mass_std_kg = 0.0;
  // One sigma of the factory gauge scale [1]; 0 holds s_i at the base file's
  // value when the tip mass is not weighed (and leaves s_i free when it is).
  // A flight fit holds s_i and adds this (relative) to the sigma of k and m_p.
  double gauge_scale_std = 0.0;

  bool TipMassWeighed() const { return std::isfinite(tip_mass_kg); }
};

// Where a fit is, for a progress line (birotor-identify prints it on stderr).
struct FitProgress {
  std::string stage;      // what runs, e.g. "flight: solve, m_p held"
  int windows = 0;        // output-error windows in the problem (0: none)
  int iteration = 0;      // solver iteration in this stage (0: the stage starts)
  double fraction = 0.0;  // share of the whole fit done before this stage, a rough estimate [0, 1]
};

struct IdentificationOptions {
  // Sensor noise, one sigma (reference sensors of reference-vehicle.md).
  double strain_noise_rad = 2e-5;      // strain gauges [rad]
  double telemetry_noise_rad_s = 5.0;  // ESC speed telemetry [rad/s]
  double loadcell_noise_n = 0.02;      // bench load cells [N]
  double gyro_noise_rad_s = 0.005;     // IMU pitch rate [rad/s]
  double accel_noise_m_s2 = 0.05;      // IMU specific force [m/s^2]
  // Thrust regression (bench): one load-cell/telemetry pair every this many
  // seconds, so that the turbulence (correlation time 0.1 s) is nearly white
  // between pairs; the turbulence std of the base parameters is added to sigma.
  double thrust_sample_spacing_s = 0.3;
  // Output-error windows (multiple shooting, each window has its own initial state).
  double motor_window_s = 1.0;      // motor speed response [s]
  double bench_arm_window_s = 0.5;  // clamped arm response [s]
  double flight_window_s = 0.3;     // free-flight arm response [s]
  int integration_substeps = 2;     // RK4 steps per sample interval of the clamped arm (bench)
  // Free flight: RK4 steps per strain interval (1 ms at 1 kHz; the arm modes
  // near 80 Hz give a k bias of about 0.1 %, far below the flight sigma).
  int flight_integration_substeps = 1;
  // Free flight: at most this many windows, spread evenly over the logs (0:
  // every window). 40 windows of 0.3 s keep k, c_T well inside 1 % on
  // flight_id at a quarter of the cost of the whole 60 s log.
  int flight_max_windows = 40;
  // Free flight: fit the hinge damping d too. Off by default: the flight
  // windows barely constrain d (flight_id: d = 0 +- 0.23 for a truth of
  // 0.25), and a large trial d makes the 1 ms RK4 step unstable; d is then
  // held at the base value and reported as not determined.
  bool flight_fit_damping = false;
  // Free flight: fit the tip mass m_p too (the arm modes give k / m_p and,
  // with m and J known, k; the accelerometer the total mass m + 2 m_p against
  // c_T omega^2). On flight_id (60 s, 40 windows) m_p comes within 1.3 % with
  // a 0.86 % sigma once the rotor turbulence is modelled (flight_turbulence_knot_s);
  // off: m_p is held at the base value (a bench identification's, 0.1 %).
  bool flight_fit_tip_mass = true;
  // Free flight: the tip mass is fitted only when, at the fit with m_p held,
  // at least this share of its information comes from the recorded data
  // rather than from the assumed turbulence statistics (flight_fit.h
  // CheckTipMass; measured share: 1.00 on hover, gentle and flight_id) [1].
  double flight_min_data_share = 0.5;
  // Free flight: spacing of the rotor-turbulence knots in each window [s]
  // (FreeArmWindowResidual: eta_i piecewise linear under the base file's
  // Gauss-Markov prior turbulence_std, turbulence_corr_time_s); 0, or a base
  // turbulence_std of 0, holds the thrust at c_T omega^2.
  double flight_turbulence_knot_s = 0.05;
  // Robust loss: Huber with this threshold on whitened residuals [sigma].
  double huber_threshold = 3.0;
  // Static deflection-force map: polynomial degree (1..3).
  int map_degree = 1;
  // Use the IMU (gyro and accelerometer) in flight identification when present.
  bool use_imu = true;
  // Refusal thresholds.
  double min_duration_s = 5.0;  // shorter logs are refused [s]
  // A sample stamped more than this after the previous one is kept only if
  // the next sample continues from it; otherwise it is a lone stamp from the
  // future, dropped as a bad stamp. Ten intervals of the slowest stream
  // (POSE, 100 Hz) [s].
  double max_time_jump_s = 0.1;
  double max_relative_sigma = 0.2;   // above: the parameter is not determined [1]
  double command_step_rad_s = 30.0;  // a command change this large in one sample is a step [rad/s]
  int min_command_steps = 2;         // fewer steps per rotor: no excitation for tau_m
  // Bench: one-sigma floors added to the statistical sigma of what the arm
  // dynamics give (relative). The load cells, sampled at 1 kHz, misrepresent
  // the force at the kinks of the motor steps and their noise drives the
  // model's resonance: measured biases on 30 s bench logs (3 seeds, 2
  // vehicles) up to 0.13 % in k / m_p and 2.6 % in d, 3 to 7 statistical
  // sigmas. The frequency floor goes to m_p (or to k and s_i when m_p is weighed).
  double bench_frequency_floor = 0.001;  // on k / m_p [1]
  double bench_damping_floor = 0.02;     // on d [1]
  // Several logs: two logs whose estimates of a parameter differ by more than
  // this many combined sigmas are refused as inconsistent [sigma].
  double consistency_sigmas = 5.0;
  // Whitened residual RMS above this is a model misfit (or heavy outliers):
  // the report says so and the sigmas are widened by the RMS [sigma].
  double misfit_rms_warn = 1.5;
  // Solver.
  int max_iterations = 50;
  int num_threads = 2;
  // The missing calibration fact (command line only, see CalibrationFact).
  CalibrationFact calibration;
  // Called at every stage and solver iteration (command line only; empty:
  // nothing is reported). Must not throw.
  std::function<void(const FitProgress&)> progress;
};

}  // namespace birotor
