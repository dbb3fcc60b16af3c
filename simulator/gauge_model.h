// The real strain gauge of scenario.h's GaugeParams (shared/spec/gauges.md),
// one copy for the birotor and the N-arm simulator:
//   b_meas_i(t) = s_i b_i(t) + o_i(t) + v_i(t) + n_i(t),
//   o_i(t) = offset_i + drift_i * (time spent inside drift_window),
//   v_i = a1_i sin(theta_i) + a2_i sin(2 theta_i + phase2_i),
// theta_i the angle of rotor i, integrated from its own speed.
#pragma once

#include <algorithm>
#include <cmath>

#include "simulator/scenario.h"

namespace birotor {

// o_i(t) of gauge `arm` (0-based) at simulated time t_s [rad].
inline double GaugeOffsetRad(const GaugeParams& gauge, int arm, double t_s) {
  const size_t i = static_cast<size_t>(arm);
  const double drift_s = std::clamp(t_s - gauge.drift_window.start_s, 0.0, gauge.drift_window.duration_s);
  return gauge.offset_rad[i] + gauge.drift_rad_s[i] * drift_s;
}

// s_i b_i + o_i(t) + v_i: the reading before the white noise n_i [rad];
// exactly b_i for the ideal gauge. deflection_rad is the true b_i,
// rotor_angle_rad theta_i.
inline double GaugeReadingRad(const GaugeParams& gauge, int arm, double deflection_rad, double t_s,
                              double rotor_angle_rad) {
  const size_t i = static_cast<size_t>(arm);
  double reading = gauge.scale[i] * deflection_rad + GaugeOffsetRad(gauge, arm, t_s);
  if (gauge.harmonic_1x_rad[i] != 0.0 || gauge.harmonic_2x_rad[i] != 0.0) {
    reading += gauge.harmonic_1x_rad[i] * std::sin(rotor_angle_rad) +
               gauge.harmonic_2x_rad[i] * std::sin(2.0 * rotor_angle_rad + gauge.harmonic_2x_phase_rad[i]);
  }
  return reading;
}

// The true deflection b_i at the jittered reading instant t + jitter_s
// (SensorParams::strain_stamp_jitter_s), to first order: b_i(t) + e b_dot_i(t) [rad].
inline double JitteredDeflectionRad(double deflection_rad, double deflection_rate_rad_s, double jitter_s) {
  return deflection_rad + jitter_s * deflection_rate_rad_s;
}

// theta_i after one step of dt_s: the trapezoid of the speeds before and
// after it [rad/s], kept in [0, 2 pi) so its precision does not decay [rad].
inline double AdvanceRotorAngleRad(double angle_rad, double omega_before_rad_s, double omega_after_rad_s, double dt_s) {
  const double angle = angle_rad + 0.5 * dt_s * (omega_before_rad_s + omega_after_rad_s);
  return angle - 2.0 * M_PI * std::floor(angle / (2.0 * M_PI));
}

}  // namespace birotor
