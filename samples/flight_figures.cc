#include "samples/flight_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "samples/motor_command.h"

namespace birotor {
namespace {

// A feed-forward term the setpoint does not give (NaN) is taken as 0.
double OrZero(double value) { return std::isfinite(value) ? value : 0.0; }

}  // namespace

bool EntersFallback(int32_t status, bool* in_fallback) {
  if ((status & kCommandNoPoseYet) != 0) return false;  // rotors at 0: says nothing about FORCE
  const bool fallback = (status & kCommandFallbackActive) != 0;
  const bool enters = fallback && !*in_fallback;
  *in_fallback = fallback;
  return enters;
}

void FlightFigures::AddSetpoint(const Setpoint& setpoint) {
  setpoint_ = setpoint;
  has_setpoint_ = true;
}

void FlightFigures::AddTruth(const TruthSample& truth) {
  values_.max_tilt_rad = std::max(values_.max_tilt_rad, std::fabs(truth.phi_rad));
  in_motion_ = in_motion_ || truth.x_dot_m_s != 0.0 || truth.z_dot_m_s != 0.0 || truth.phi_dot_rad_s != 0.0;
  if (!in_motion_ || !has_setpoint_) return;
  // The reference at the sample's time: p + v dt + a dt^2 / 2 [m].
  const double dt_s = 1e-6 * static_cast<double>(truth.utime - setpoint_.utime);
  const double x_ref_m =
      setpoint_.x_m + OrZero(setpoint_.x_dot_m_s) * dt_s + 0.5 * OrZero(setpoint_.x_ddot_m_s2) * dt_s * dt_s;
  const double z_ref_m =
      setpoint_.z_m + OrZero(setpoint_.z_dot_m_s) * dt_s + 0.5 * OrZero(setpoint_.z_ddot_m_s2) * dt_s * dt_s;
  const double dx_m = truth.x_m - x_ref_m;
  const double dz_m = truth.z_m - z_ref_m;
  sum_squared_m2_ += dx_m * dx_m + dz_m * dz_m;
  ++values_.scored_samples;
}

void FlightFigures::AddCommand(int32_t status) {
  if (EntersFallback(status, &in_fallback_)) ++values_.fallbacks;
  if ((status & kCommandFallbackActive) != 0) ++values_.fallback_commands;
  if ((status & kCommandMpcFallback) != 0) ++values_.mpc_fallbacks;
}

std::string FlightFigureValues::Line() const {
  char rms[48] = "- (no SETPOINT)";
  if (std::isfinite(rms_position_error_m)) std::snprintf(rms, sizeof(rms), "%.4f m", rms_position_error_m);
  char line[192];
  std::snprintf(line, sizeof(line), "RMS position error %s, max tilt %.4f rad, fallbacks %lld, MPC fallbacks %lld", rms,
                max_tilt_rad, static_cast<long long>(fallbacks), static_cast<long long>(mpc_fallbacks));
  return line;
}

FlightFigureValues FlightFigures::Result() const {
  FlightFigureValues out = values_;
  out.rms_position_error_m = out.scored_samples > 0
                                 ? std::sqrt(sum_squared_m2_ / static_cast<double>(out.scored_samples))
                                 : std::numeric_limits<double>::quiet_NaN();
  return out;
}

}  // namespace birotor
