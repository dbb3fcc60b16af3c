#ifndef BIROTOR_SIMULATOR_FLOWN_VEHICLE_H_
#define BIROTOR_SIMULATOR_FLOWN_VEHICLE_H_

// The vehicle a scenario flies when it is given a description with N arms.
//
// A scenario's `vehicle:` section is a birotor (params/scenario_yaml.h). On a
// description it says how the flown vehicle differs from the one in its
// file, relative to the reference birotor (BirotorParams' defaults, the
// birotor of config/reference_vehicle.yaml): each physical field's ratio to
// the reference's multiplies the matching field of the description, on every
// arm. mismatch_stiffness_plus20 (k 2628 -> 3153.6 N m/rad) therefore flies
// every arm 20 % stiffer on any vehicle, and a scenario whose section is the
// reference's flies the description bit for bit (ratio exactly 1).
//
// Scaled: body mass, body inertia, gravity, omega_max, the turbulence's std
// and correlation time; per arm the length, stiffness, damping, tip mass,
// c_T and tau_m. Not scaled: the geometry's angles and spins, has_gauge, and
// the gauge fields (gauge_scale, gauge_offset_rad and the offset priors are
// what an estimator believes; the true gauges are the scenario's gauge:
// section).

#include "model/vehicle_description.h"

namespace birotor {

// description with every scaled field times scenario_vehicle's over the
// reference birotor's (scenario_vehicle: Scenario::vehicle, birotor form).
VehicleDescription FlownVehicle(const VehicleDescription& description, const VehicleDescription& scenario_vehicle);

}  // namespace birotor

#endif  // BIROTOR_SIMULATOR_FLOWN_VEHICLE_H_
