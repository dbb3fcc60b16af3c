#include "evaluation/descent_floor.h"

#include <algorithm>
#include <cmath>

#include "samples/motor_command.h"

namespace birotor {
namespace {

// A body this close to the support is on it (as control_metrics.cc's contact) [m].
constexpr double kOnSupportM = 1e-3;

}  // namespace

double WeakestFinalThrustScale(const Scenario& scenario) {
  double scale[2] = {scenario.faults.initial_thrust_scale[0], scenario.faults.initial_thrust_scale[1]};
  for (const ThrustStep& step : scenario.faults.thrust_steps) {
    if (step.rotor == 1 || step.rotor == 2) scale[step.rotor - 1] = step.scale;
  }
  return std::min(scale[0], scale[1]);
}

double LevelSinkAccelM_S2(const Scenario& scenario) {
  const BirotorParams v = BirotorModelOf(scenario.vehicle);
  const double mass_kg = v.body_mass_kg + 2.0 * v.tip_mass_kg;
  const double max_rotor_n = v.thrust_coeff_n_s2_rad2 * v.omega_max_rad_s * v.omega_max_rad_s;
  return v.gravity_m_s2 - 2.0 * WeakestFinalThrustScale(scenario) * max_rotor_n / mass_kg;
}

DescentFloor LevelDescentFloor(const ClosedLoopRun& run, const Scenario& scenario) {
  DescentFloor floor;
  if (!run.has_ground || run.fault_utime < 0 || run.samples.empty()) return floor;
  int64_t start_utime = -1;
  for (const MotorCommand& c : run.commands) {
    if (c.utime >= run.fault_utime && (c.status & kCommandDescending) != 0) {
      start_utime = c.utime;
      break;
    }
  }
  if (start_utime < 0) return floor;
  for (const TrackedSample& s : run.samples) {
    if (s.truth.utime < start_utime) continue;
    // A "descent" that starts on the support (POSE gated after a crash) is none.
    floor.found = s.truth.z_m > run.ground_z_m + kOnSupportM;
    floor.start_s = 1e-6 * static_cast<double>(s.truth.utime - run.samples.front().truth.utime);
    floor.height_m = s.truth.z_m - run.ground_z_m;
    floor.climb_m_s = s.truth.z_dot_m_s;
    break;
  }
  floor.sink_accel_m_s2 = LevelSinkAccelM_S2(scenario);
  const double energy = floor.climb_m_s * floor.climb_m_s + 2.0 * floor.sink_accel_m_s2 * floor.height_m;
  floor.touchdown_m_s = std::sqrt(std::max(energy, 0.0));
  return floor;
}

}  // namespace birotor
