// Output of the identification: the parameter file the estimator and the
// simulator load (a full `vehicle:` section, uncertainties and the
// deflection-force maps as comments) and a readable report. The tool writes
// them through transport/output_file.h. Here, beside the reader of the same
// file, so that the keys are written from the reader's table.
#pragma once

#include <string>

#include "identification/identification_result.h"

namespace birotor {

// YAML text: comment header (sources, one-sigma values, maps, residuals)
// followed by VehicleParamsYaml(result.params).
std::string IdentifiedParameterYaml(const IdentificationResult& result);

// Markdown report: parameters with value, sigma, relative sigma and status,
// residual RMS per residual block, maps, undetermined parameters, warnings.
std::string IdentificationReport(const IdentificationResult& result);

}  // namespace birotor
