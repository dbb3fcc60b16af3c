#include "controller/rotor_allocation.h"

#include <algorithm>
#include <cmath>

#include "controller/position_attitude_law.h"
#include "samples/rotor_count.h"

namespace birotor {

RotorAllocation AllocateAttitudeFirst(double total_force_n, double force_difference_n,
                                      const double (&max_force_n)[kBirotorRotors]) {
  RotorAllocation out;
  const double max1 = std::max(max_force_n[0], 0.0), max2 = std::max(max_force_n[1], 0.0);
  // The largest |D| both rotors can make: f2 - f1 in [-max1, max2].
  const double difference = std::clamp(force_difference_n, -max1, max2);
  out.difference_limited = difference != force_difference_n;
  const double lowest = std::fabs(difference);
  const double highest = std::max(lowest, std::min(2.0 * max1 + difference, 2.0 * max2 - difference));
  const double total = std::clamp(total_force_n, lowest, highest);
  out.total_limited = total != total_force_n;
  out.force_n[0] = std::clamp(0.5 * (total - difference), 0.0, max1);
  out.force_n[1] = std::clamp(0.5 * (total + difference), 0.0, max2);
  return out;
}

FlareState FlareStateOf(const BodyState& body, double ground_z_m) {
  FlareState state;
  state.height_m = body.position_m.y() - ground_z_m;
  state.sink_rate_m_s = -body.velocity_m_s.y();
  state.tilt_rad = body.phi_rad;
  state.pitch_rate_rad_s = body.phi_dot_rad_s;
  return state;
}

bool InFlareWindow(const FlareState& state, double tilt_budget_rad, double descent_rate_m_s, double flare_time_s) {
  return tilt_budget_rad > 0.0 && state.sink_rate_m_s > descent_rate_m_s && state.height_m > 0.0 &&
         state.height_m <= state.sink_rate_m_s * flare_time_s;
}

FlareForces FlareForcesFor(const FlareState& state, const FlareLimits& limits) {
  FlareForces out;
  const bool rotor2_strong = limits.max_force_n[1] > limits.max_force_n[0];
  const double sign = rotor2_strong ? 1.0 : -1.0;
  const double max_weak = std::max(std::min(limits.max_force_n[0], limits.max_force_n[1]), 0.0);
  const double max_strong = std::max(limits.max_force_n[0], limits.max_force_n[1]);
  const double sink_m_s = std::max(state.sink_rate_m_s, 1e-6);
  out.time_to_go_s = std::max(std::max(state.height_m, 0.0) / sink_m_s, limits.min_time_to_go_s);
  const double t = std::max(out.time_to_go_s, 1e-6);
  const double tilt_left_rad = limits.tilt_budget_rad - sign * (state.tilt_rad + state.pitch_rate_rad_s * t);
  const double extra_n = 2.0 * limits.pitch_inertia_kg_m2 * tilt_left_rad / (limits.arm_length_m * t * t);
  // A non-finite state asks for nothing (the caller's guard sees the law's output).
  out.extra_force_n = std::isfinite(extra_n) ? std::clamp(extra_n, 0.0, std::max(max_strong - max_weak, 0.0)) : 0.0;
  out.total_force_n = 2.0 * max_weak + out.extra_force_n;
  out.force_difference_n = sign * out.extra_force_n;
  return out;
}

}  // namespace birotor
