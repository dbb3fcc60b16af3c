// Robust weighting of single residuals inside a residual block. Ceres' loss
// functions act on a whole block's squared norm, which for an output-error
// window of hundreds of samples would not reject an isolated spike.
#pragma once

#include <cmath>

namespace birotor {

// Huber in residual form: r' = r for |r| <= c, sign(r) sqrt(2 c |r| - c^2)
// beyond, so that r'^2 / 2 is the Huber cost of the whitened residual r
// (quadratic inside c sigma, linear outside). c <= 0 disables it.
template <typename T>
T HuberResidual(const T& r, double c) {
  using std::sqrt;
  if (c <= 0.0) return r;
  if (r > T(c)) return sqrt(2.0 * c * r - c * c);
  if (r < T(-c)) return -sqrt(-2.0 * c * r - c * c);
  return r;
}

}  // namespace birotor
