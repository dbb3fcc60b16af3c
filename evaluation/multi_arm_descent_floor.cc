#include "evaluation/multi_arm_descent_floor.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace birotor {

std::array<double, kMaxArms> FinalThrustScales(const Scenario& scenario) {
  std::array<double, kMaxArms> scale{};
  for (size_t i = 0; i < scale.size(); ++i) scale[i] = scenario.faults.initial_thrust_scale[i];
  for (const ThrustStep& step : scenario.faults.thrust_steps) {
    if (step.rotor >= 1 && step.rotor <= kMaxArms) scale[static_cast<size_t>(step.rotor - 1)] = step.scale;
  }
  return scale;
}

double MultiArmLevelSinkAccelM_S2(const VehicleDescription& vehicle, const MultiArmHover& hover,
                                  const std::array<double, kMaxArms>& scale) {
  double lambda = 1.0;
  for (int i = 0; i < vehicle.arm_count; ++i) {
    const size_t rotor = static_cast<size_t>(i);
    const double max_n =
        scale[rotor] * vehicle.arms[rotor].thrust_coeff_n_s2_rad2 * vehicle.omega_max_rad_s * vehicle.omega_max_rad_s;
    lambda = std::min(lambda, max_n / hover.force_n(i));
  }
  return vehicle.gravity_m_s2 * (1.0 - lambda);
}

MultiArmDescent MultiArmDescentOf(const MultiArmClosedLoopRun& run, const VehicleDescription& vehicle,
                                  const Scenario& scenario) {
  MultiArmDescent descent;
  descent.touchdown_m_s = std::numeric_limits<double>::quiet_NaN();
  if (run.fault_utime < 0 || run.samples.empty()) return descent;
  const double ground_z_m = scenario.start_position_m[1];
  const MultiArmHover hover = SolveMultiArmHover(vehicle);
  descent.sink_accel_m_s2 = MultiArmLevelSinkAccelM_S2(vehicle, hover, FinalThrustScales(scenario));
  // Without a descent (the nominal map) from the fault on.
  const int64_t start_utime = run.descent_utime >= 0 ? run.descent_utime : run.fault_utime;
  bool started = false;
  for (const MultiArmTrackedSample& s : run.samples) {
    if (s.utime < run.fault_utime) continue;
    descent.peak_tilt_rad = std::max(descent.peak_tilt_rad, std::abs(s.phi_rad));
    if (!started && s.utime >= start_utime) {
      started = true;
      descent.found = run.descent_utime >= 0 && s.position_m.y() > ground_z_m;
      descent.start_s = 1e-6 * static_cast<double>(s.utime - run.samples.front().utime);
      descent.height_m = s.position_m.y() - ground_z_m;
      descent.climb_m_s = s.velocity_m_s.y();
    }
    if (started && s.position_m.y() <= ground_z_m) {
      descent.touchdown_m_s = std::max(-s.velocity_m_s.y(), 0.0);
      break;
    }
  }
  const double energy = descent.climb_m_s * descent.climb_m_s + 2.0 * descent.sink_accel_m_s2 * descent.height_m;
  descent.floor_m_s = std::sqrt(std::max(energy, 0.0));
  return descent;
}

}  // namespace birotor
