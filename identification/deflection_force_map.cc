#include "identification/deflection_force_map.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace birotor {

DeflectionForceMap FitDeflectionForceMap(int arm, const std::vector<double>& deflection_rad,
                                         const std::vector<double>& force_n, int degree) {
  DeflectionForceMap map;
  map.arm = arm;
  const int n = static_cast<int>(std::min(deflection_rad.size(), force_n.size()));
  const int terms = degree + 1;
  if (n <= terms) return map;
  // Columns in a scaled deflection u = b / b_scale keep A^T A well conditioned.
  double b_scale = 0.0;
  for (int i = 0; i < n; ++i) b_scale = std::max(b_scale, std::abs(deflection_rad[i]));
  if (b_scale <= 0.0) return map;
  Eigen::MatrixXd a(n, terms);
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) {
    const double u = deflection_rad[i] / b_scale;
    double power = 1.0;
    for (int j = 0; j < terms; ++j, power *= u) a(i, j) = power;
    y(i) = force_n[i];
  }
  const Eigen::MatrixXd ata = a.transpose() * a;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(ata);
  const Eigen::VectorXd coeff_scaled = ldlt.solve(a.transpose() * y);
  const Eigen::VectorXd residual = y - a * coeff_scaled;
  const double variance = residual.squaredNorm() / (n - terms);
  const Eigen::MatrixXd cov = ldlt.solve(Eigen::MatrixXd::Identity(terms, terms)) * variance;
  map.coefficients.resize(terms);
  map.sigmas.resize(terms);
  for (int j = 0; j < terms; ++j) {
    const double unscale = std::pow(b_scale, -j);
    map.coefficients[j] = coeff_scaled(j) * unscale;
    map.sigmas[j] = std::sqrt(std::max(0.0, cov(j, j))) * unscale;
  }
  map.residual_rms_n = std::sqrt(residual.squaredNorm() / n);
  map.deflection_min_rad = *std::min_element(deflection_rad.begin(), deflection_rad.begin() + n);
  map.deflection_max_rad = *std::max_element(deflection_rad.begin(), deflection_rad.begin() + n);
  map.samples = n;
  return map;
}

double EvaluateMap(const DeflectionForceMap& map, double deflection_rad) {
  double value = 0.0;
  for (auto it = map.coefficients.rbegin(); it != map.coefficients.rend(); ++it) value = value * deflection_rad + *it;
  return value;
}

}  // namespace birotor
