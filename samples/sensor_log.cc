#include "samples/sensor_log.h"

#include <cmath>

namespace birotor {

double StrainDurationS(const SensorLog& log) {
  if (log.strain.size() < 2) return 0.0;
  return 1e-6 * static_cast<double>(log.strain.back().utime - log.strain.front().utime);
}

bool HasMotorTelemetry(const SensorLog& log) {
  for (const MotorSample& m : log.motor) {
    if (std::isfinite(m.omega_meas_rad_s[0]) && std::isfinite(m.omega_meas_rad_s[1])) return true;
  }
  return false;
}

}  // namespace birotor
