// Output of the identification: the parameter file the estimator and the
// simulator load (a full `vehicle:` section, uncertainties and the
// deflection-force maps as comments), a readable report, and atomic writing.
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

// Writes text to path so that a crash never leaves a half-written file: a
// temporary file in the same directory, fsync, rename over path, fsync of the
// directory. False (with *error) on failure; the old file is then untouched.
bool WriteFileAtomically(const std::string& path, const std::string& text, std::string* error);

}  // namespace birotor
