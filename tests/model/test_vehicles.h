// The vehicles the N-arm model tests use: the reference birotor
// (BirotorDescription of the reference parameters) and the shipped trirotor,
// loaded from config/vehicles/trirotor.yaml, so the tests assert the figures
// of the vehicle users fly and birotor-analyze --vehicle prints. A test that
// includes this needs SOURCE_TREE and birotor_params (tests/model/CMakeLists.txt).
#pragma once

#include <string>

#include "model/birotor_params.h"
#include "model/vehicle_description.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace test_vehicles {

inline std::string SourceFile(const std::string& relative_path) {
  return std::string(BIROTOR_SOURCE_DIR) + "/" + relative_path;
}

// The birotor of the reference file: arm 1 along body -x, arm 2 along +x, thrust up.
inline VehicleDescription Birotor(const BirotorParams& p = BirotorParams()) { return BirotorDescription(p); }

// config/vehicles/trirotor.yaml: arms at alpha = 180, -45, 45 deg, thrusts at
// theta = 0, -45, 45 deg (perpendicular to the arms, levers -L, +L, +L), a
// gauge on every arm (docs/vehicle-description.md, "The trirotor").
inline VehicleDescription Trirotor() {
  static const VehicleDescription loaded = LoadVehicleDescription(SourceFile("config/vehicles/trirotor.yaml"));
  return loaded;
}

// The trirotor with arm `arm_1based`'s gauge taken away (thesis 7.3.2's two
// gauges; birotor-analyze --without-gauge names it the same way).
inline VehicleDescription TrirotorWithoutGauge(int arm_1based) {
  VehicleDescription vehicle = Trirotor();
  vehicle.arms[static_cast<size_t>(arm_1based - 1)].has_gauge = false;
  vehicle.name += ", no gauge on arm " + std::to_string(arm_1based);
  return vehicle;
}

}  // namespace test_vehicles
}  // namespace birotor
