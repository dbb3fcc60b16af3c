// birotor-estimator --vehicle FILE: the live daemon for a vehicle
// description with N arms. Subscribes to STRAIN_N, MOTOR_N and IMU (the
// N-arm filter uses no POSE), publishes one FORCE_N per accepted strain
// sample and ESTIMATOR_STATUS at --status-rate-hz (host clock), through
// nodes/multi_arm_estimator_service.h, the code birotor-replay --vehicle
// runs; stops on SIGINT/SIGTERM. FORCE_N goes out sealed (FORCE_N_AUTH,
// then the plain copy) unless the site lets it through unsigned
// (docs/interface.md, "Authenticated channels").
#pragma once

#include <string>

#include "estimator/estimator_config.h"
#include "nodes/estimator_service.h"
#include "program/channel_security.h"

namespace birotor {

struct VehicleEstimatorOptions {
  std::string vehicle_file;  // --vehicle
  std::string params_file;   // --params (its estimator: section; for the start-up line)
  std::string lcm_url;       // --lcm-url
  std::string prefix;        // --prefix
  EstimatorServiceOptions service;
  int realtime_priority = 0;  // --realtime-priority
};

// Runs the daemon until a signal; the exit status (1 with one line when the
// description, LCM or the subscription fails). security: loaded for FORCE_N.
int RunVehicleEstimator(const VehicleEstimatorOptions& options, EstimatorConfig config,
                        const ChannelSecurity& security);

}  // namespace birotor
