// Jets of one arm scattered into the Jets of the whole N-arm process
// Jacobian: arm i's share of M, C, G and tau (model/arm_terms.h) depends on 4
// of the Jacobian's 1 + 3N variables (b_i, phi_dot, b_dot_i, f_i), so it is
// computed with Jet<double, 4> and added into the Jet<double, 1 + 3N> terms
// at those 4 columns. The sums are the ones the wide Jets would do (the other
// columns of an arm's wide Jet are exact zeros, and x + 0 = x), at a third
// of the cost. docs/estimator.md, "The EKF for N arms".
#pragma once

#include <ceres/jet.h>

#include <array>
#include <cmath>

#include "model/multi_arm_dynamics.h"

namespace birotor {

// Variables of one arm's Jet, in this order: b_i, phi_dot, b_dot_i, f_i.
inline constexpr int kArmJetSize = 4;
using ArmJet = ceres::Jet<double, kArmJetSize>;
enum ArmJetVariable { kArmJetDeflection = 0, kArmJetPitchRate = 1, kArmJetDeflectionRate = 2, kArmJetForce = 3 };

// One entry of a wide-Jet vector or matrix that an arm adds to: += an arm
// Jet adds its value and its 4 derivatives at the wide columns; += a double
// adds to the value only (a constant).
template <int K>
class ScatteredJetEntry {
 public:
  ScatteredJetEntry(ceres::Jet<double, K>* target, const std::array<int, kArmJetSize>& columns)
      : target_(target), columns_(columns) {}
  void operator+=(double constant) { target_->a += constant; }
  void operator+=(const ArmJet& x) {
    target_->a += x.a;
    for (int j = 0; j < kArmJetSize; ++j) target_->v(columns_[static_cast<size_t>(j)]) += x.v(j);
  }

 private:
  ceres::Jet<double, K>* target_;
  const std::array<int, kArmJetSize>& columns_;
};

// The Matrix and Vector of AddArmTerms over MultiArmTerms<Jet<double, K>>.
template <int K>
class ScatteredJetMatrix {
 public:
  ScatteredJetMatrix(MultiCoordMatrix<ceres::Jet<double, K>>* target, const std::array<int, kArmJetSize>& columns)
      : target_(target), columns_(columns) {}
  ScatteredJetEntry<K> operator()(int r, int c) { return ScatteredJetEntry<K>(&(*target_)(r, c), columns_); }

 private:
  MultiCoordMatrix<ceres::Jet<double, K>>* target_;
  const std::array<int, kArmJetSize>& columns_;
};

template <int K>
class ScatteredJetVector {
 public:
  ScatteredJetVector(MultiCoords<ceres::Jet<double, K>>* target, const std::array<int, kArmJetSize>& columns)
      : target_(target), columns_(columns) {}
  ScatteredJetEntry<K> operator()(int r) { return ScatteredJetEntry<K>(&(*target_)(r), columns_); }

 private:
  MultiCoords<ceres::Jet<double, K>>* target_;
  const std::array<int, kArmJetSize>& columns_;
};

// sin x and cos x of a double and of a Jet from its value's: (sin a, cos a v)
// and (cos a, -sin a v), as ceres' sin and cos, whose separate calls each take
// their own sin and cos of a. A double within kSmallAngleRad (the arms'
// deflections, ~1e-3 rad) by the Taylor series to x^9 and x^10 in Horner form:
// the first terms left out, x^11 / 11! and x^12 / 12!, are below 1e-19 x and
// 1e-23 there, so the result is the library's to rounding (a few 1e-17; tests/
// estimator/multi_arm_ekf_model_test.cc to 4e-16) at a quarter of its cost;
// beyond it the library's sin and cos.
inline constexpr double kSmallAngleRad = 0.0625;
inline void SinCos(double x, double* sin_x, double* cos_x) {
  if (!(std::abs(x) <= kSmallAngleRad)) {  // and NaN
    *sin_x = std::sin(x);
    *cos_x = std::cos(x);
    return;
  }
  const double x2 = x * x;
  *sin_x = x + x * x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 * (1.0 / 362880))));
  *cos_x = 1.0 + x2 * (-0.5 + x2 * (1.0 / 24 + x2 * (-1.0 / 720 + x2 * (1.0 / 40320 + x2 * (-1.0 / 3628800)))));
}
template <int K>
void SinCos(const ceres::Jet<double, K>& x, ceres::Jet<double, K>* sin_x, ceres::Jet<double, K>* cos_x) {
  double s = 0.0, c = 0.0;
  SinCos(x.a, &s, &c);
  *sin_x = ceres::Jet<double, K>(s, c * x.v);
  *cos_x = ceres::Jet<double, K>(c, -s * x.v);
}

// Adds arm i's share, computed on arm Jets, to the wide-Jet terms: columns[j]
// is the wide column of arm variable j (ArmJetVariable order).
template <int K>
void AddScatteredArmTerms(const ArmShare<ArmJet>& share, int b, const std::array<int, kArmJetSize>& columns,
                          MultiArmTerms<ceres::Jet<double, K>>* terms) {
  ScatteredJetMatrix<K> mass(&terms->mass, columns);
  ScatteredJetVector<K> coriolis(&terms->coriolis, columns);
  ScatteredJetVector<K> gravity_spring(&terms->gravity_spring, columns);
  ScatteredJetVector<K> generalized_thrust(&terms->generalized_thrust, columns);
  AddArmTerms(share, b, &mass, &coriolis, &gravity_spring, &generalized_thrust);
}

}  // namespace birotor
