// The text birotor-analyze prints for a vehicle description: the hover, the
// arm modes, controllability and the force-observability table of
// model/vehicle_analysis.h, as Markdown (docs/multi-arm-model.md shows it).
#pragma once

#include <string>

#include "model/vehicle_analysis.h"
#include "model/vehicle_description.h"

namespace birotor {

// Label of one measurement set in the table ("gauges (b1, b2)", ...).
std::string MeasurementSetLabel(const VehicleDescription& vehicle, VehicleMeasurementSet measured);

// "[0.12, -0.21, -0.97]": a force direction with two decimals.
std::string ForceDirectionText(const Eigen::VectorXd& direction);

// The whole report for analysis = AnalyzeVehicle(vehicle).
std::string VehicleAnalysisText(const VehicleDescription& vehicle, const VehicleAnalysis& analysis);

}  // namespace birotor
