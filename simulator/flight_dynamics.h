// The free-flight plant derivative the simulator integrates: the same
// equations as PlantDerivative of model/plant.h (ComputeDynamicsTerms,
// thesis eq. 3.14), with the 5x5 mass-matrix solve done by an unrolled LDL^T
// instead of Eigen's generic LLT, which took ~40 % of the simulation time.
#pragma once

#include "model/plant.h"

namespace birotor {

// Solves M x = rhs for a symmetric positive definite M (the mass matrix) by
// M = L D L^T with unit lower-triangular L; no square roots.
inline Coords<double> SolveMassMatrix(const CoordMatrix<double>& M, const Coords<double>& rhs) {
  constexpr int n = kNumCoordinates;
  double lower[n][n] = {};
  double diagonal[n];
  for (int j = 0; j < n; ++j) {
    double d = M(j, j);
    for (int k = 0; k < j; ++k) d -= lower[j][k] * lower[j][k] * diagonal[k];
    diagonal[j] = d;
    for (int i = j + 1; i < n; ++i) {
      double s = M(i, j);
      for (int k = 0; k < j; ++k) s -= lower[i][k] * lower[j][k] * diagonal[k];
      lower[i][j] = s / d;
    }
  }
  double y[n];
  for (int i = 0; i < n; ++i) {
    double s = rhs(i);
    for (int k = 0; k < i; ++k) s -= lower[i][k] * y[k];
    y[i] = s;
  }
  Coords<double> x;
  for (int i = n - 1; i >= 0; --i) {
    double s = y[i] / diagonal[i];
    for (int k = i + 1; k < n; ++k) s -= lower[k][i] * x(k);
    x(i) = s;
  }
  return x;
}

// PlantDerivative (model/plant.h) with SolveMassMatrix:
//   q_dot = v,  v_dot = M^-1 (tau - C - G),  omega_i_dot = (clamp(omega_cmd_i) - omega_i) / tau_m.
inline PlantState FlightDerivative(const VehicleParams& p, const PlantState& x, const PlantInput& u) {
  const Coords<double> q = x.segment<kNumCoordinates>(kPlantQ);
  const Coords<double> v = x.segment<kNumCoordinates>(kPlantV);
  const double f1 = RotorThrust(p, x(kPlantOmega1), u.thrust_scale[0]);
  const double f2 = RotorThrust(p, x(kPlantOmega2), u.thrust_scale[1]);
  const DynamicsTerms<double> terms = ComputeDynamicsTerms<double>(p, q, v, f1, f2);
  PlantState x_dot;
  x_dot.segment<kNumCoordinates>(kPlantQ) = v;
  x_dot.segment<kNumCoordinates>(kPlantV) =
      SolveMassMatrix(terms.mass, terms.generalized_thrust - terms.coriolis - terms.gravity_spring);
  x_dot(kPlantOmega1) = (ClampCommand(p, u.omega_cmd_rad_s[0]) - x(kPlantOmega1)) / p.motor_time_constant_s;
  x_dot(kPlantOmega2) = (ClampCommand(p, u.omega_cmd_rad_s[1]) - x(kPlantOmega2)) / p.motor_time_constant_s;
  return x_dot;
}

}  // namespace birotor
