// Static deflection-force map of one arm from bench data, the way the strain
// gauges are first calibrated on a test stand: force as a low-order
// polynomial of deflection, fitted by linear least squares.
#pragma once

#include <vector>

#include "identification/identification_result.h"

namespace birotor {

// Fits force_n = sum_{j=0..degree} c_j b^j to paired samples (degree 1..3).
// Coefficient sigmas from (A^T A)^-1 scaled by the residual variance.
// Returns a map with samples = 0 when there are fewer samples than coefficients.
DeflectionForceMap FitDeflectionForceMap(int arm, const std::vector<double>& deflection_rad,
                                         const std::vector<double>& force_n, int degree);

// Evaluates the map at a deflection [N].
double EvaluateMap(const DeflectionForceMap& map, double deflection_rad);

}  // namespace birotor
