// The text birotor-analyze prints for a vehicle description: the hover, the
// arm modes, controllability and the force-observability table of
// model/vehicle_analysis.h, as Markdown (docs/multi-arm-model.md shows it);
// and the vehicle of its --without-gauge option.
#pragma once

#include <string>
#include <vector>

#include "model/vehicle_analysis.h"
#include "model/vehicle_description.h"

namespace birotor {

// The vehicle with the gauges of the given arms removed (1-based, as in the
// file: birotor-analyze --without-gauge), named "<name>, no gauge on arm 3"
// ("arms 1, 3"). False, with *why, when an arm number is outside
// [1, arm_count], names an arm without a gauge, or no gauge would remain.
bool VehicleWithoutGauges(const VehicleDescription& vehicle, const std::vector<int>& arms_1based,
                          VehicleDescription* out, std::string* why);

// Label of one measurement set in the table ("gauges (b1, b2)", ...).
std::string MeasurementSetLabel(const VehicleDescription& vehicle, VehicleMeasurementSet measured);

// "[0.12, -0.21, -0.97]": a force direction with two decimals.
std::string ForceDirectionText(const Eigen::VectorXd& direction);

// The whole report for analysis = AnalyzeVehicle(vehicle).
std::string VehicleAnalysisText(const VehicleDescription& vehicle, const VehicleAnalysis& analysis);

}  // namespace birotor
