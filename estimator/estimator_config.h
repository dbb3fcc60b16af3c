// Options of the force estimator (method, filter tuning, gates, timeouts),
// with the reference vehicle; every field has a documented default and is
// loaded from the `estimator:` section of a parameter file by params/.
#pragma once

#include <string>

#include "estimator/vehicle_params.h"

namespace birotor {

struct EstimatorConfig {
  VehicleParams vehicle;           // `vehicle:` section
  std::string method = "ekf";      // "ekf", "inversion" or "motor_map"
  // (The implementer of the estimator library adds the EKF tuning, gate,
  // staleness, reset and inversion options here, each with a default and a
  // unit in its name.)
};

}  // namespace birotor
