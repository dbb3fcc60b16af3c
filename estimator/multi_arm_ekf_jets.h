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
