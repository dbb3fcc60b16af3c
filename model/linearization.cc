#include "model/linearization.h"

#include <ceres/jet.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace birotor {

LinearModel Linearize(const BirotorParams& p, const Coords<double>& q0, const Coords<double>& v0, double force1_n,
                      double force2_n) {
  using Jet = ceres::Jet<double, kMechStateSize + 2>;
  Coords<Jet> q, v;
  for (int i = 0; i < kNumCoordinates; ++i) {
    q(i) = Jet(q0(i), i);
    v(i) = Jet(v0(i), kNumCoordinates + i);
  }
  const Jet f1(force1_n, kMechStateSize), f2(force2_n, kMechStateSize + 1);
  const Coords<Jet> acc = GeneralizedAcceleration<Jet>(p, q, v, f1, f2);

  LinearModel model;
  model.a.setZero();
  model.b.setZero();
  model.a.block<kNumCoordinates, kNumCoordinates>(0, kNumCoordinates).setIdentity();
  for (int i = 0; i < kNumCoordinates; ++i) {
    model.a.row(kNumCoordinates + i) = acc(i).v.head<kMechStateSize>().transpose();
    model.b.row(kNumCoordinates + i) = acc(i).v.tail<2>().transpose();
  }
  return model;
}

LinearModel LinearizeAtHover(const BirotorParams& p) {
  const Equilibrium eq = SolveHoverEquilibrium(p);
  Coords<double> q0 = Coords<double>::Zero();
  q0(kB1) = eq.deflection_rad[0];
  q0(kB2) = eq.deflection_rad[1];
  return Linearize(p, q0, Coords<double>::Zero(), eq.force_n[0], eq.force_n[1]);
}

LinearModel ToSumDifferenceCoordinates(const LinearModel& model) {
  MechMatrix t = MechMatrix::Identity();
  for (int offset : {0, kNumCoordinates}) {
    t(offset + kB1, offset + kB1) = 1.0;  // b_s = b1 + b2
    t(offset + kB1, offset + kB2) = 1.0;
    t(offset + kB2, offset + kB1) = 1.0;  // b_d = b1 - b2
    t(offset + kB2, offset + kB2) = -1.0;
  }
  LinearModel out;
  out.a = t * model.a * t.inverse();
  out.b = t * model.b;
  return out;
}

AugMatrix AugmentWithForces(const LinearModel& model) {
  AugMatrix aug = AugMatrix::Zero();
  aug.topLeftCorner<kMechStateSize, kMechStateSize>() = model.a;
  aug.topRightCorner<kMechStateSize, 2>() = model.b;
  return aug;
}

const std::vector<std::string>& AugmentedStateNames() {
  static const std::vector<std::string> names = {"x",     "z",       "phi",    "b1",     "b2", "x_dot",
                                                 "z_dot", "phi_dot", "b1_dot", "b2_dot", "f1", "f2"};
  return names;
}

namespace {

// One body for the fixed 10 x 10 birotor matrix and dynamic sizes.
template <typename Matrix>
std::vector<Mode> ModesOf(const Matrix& a) {
  Eigen::EigenSolver<Matrix> solver(a, false);
  std::vector<Mode> modes;
  for (int i = 0; i < a.rows(); ++i) {
    const std::complex<double> lambda = solver.eigenvalues()(i);
    // One of each conjugate pair; skip the rigid-body (zero) eigenvalues.
    if (lambda.imag() <= 0 || std::abs(lambda) < 1e-3) continue;
    Mode mode;
    mode.frequency_hz = std::abs(lambda) / (2.0 * M_PI);
    mode.damping_ratio = -lambda.real() / std::abs(lambda);
    modes.push_back(mode);
  }
  std::sort(modes.begin(), modes.end(), [](const Mode& x, const Mode& y) { return x.frequency_hz < y.frequency_hz; });
  return modes;
}

}  // namespace

std::vector<Mode> OscillatoryModes(const MechMatrix& a) { return ModesOf(a); }

std::vector<Mode> OscillatoryModes(const Eigen::MatrixXd& a) { return ModesOf(a); }

}  // namespace birotor
