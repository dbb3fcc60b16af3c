// Arm mode shapes of the N-arm hover linearization.
#include "model/multi_arm_modes.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <complex>

#include "model/multi_arm_linearization.h"

namespace birotor {
namespace {

// The real shape of a lightly damped mode from its eigenvector's b rows.
Eigen::VectorXd RealShape(const Eigen::VectorXcd& b) {
  Eigen::Index largest = 0;
  b.cwiseAbs().maxCoeff(&largest);
  const std::complex<double> rotation = std::conj(b(largest)) / std::abs(b(largest));
  Eigen::VectorXd shape = (b * rotation).real();
  return shape / shape.cwiseAbs().maxCoeff();
}

// Whether `other` is another mode than `mode`, within band_fraction of its frequency.
bool OtherInBand(const ArmModeShape& mode, const ArmModeShape& other, double band_fraction) {
  return &other != &mode && std::fabs(other.frequency_hz / mode.frequency_hz - 1.0) <= band_fraction;
}

}  // namespace

std::vector<ArmModeShape> MultiArmModeShapes(const VehicleDescription& vehicle) {
  const MultiArmHover hover = SolveMultiArmHover(vehicle);
  const MultiArmLinearModel model = LinearizeMultiArmAtHover(vehicle, hover);
  const Eigen::Index n = model.a.rows() / 2;  // coordinates x, z, phi, b_1 .. b_N
  const int arms = vehicle.arm_count;
  Eigen::EigenSolver<Eigen::MatrixXd> solver(model.a, true);
  // Left eigenvectors: the rows of V^-1 (z = V^-1 x, the modal coordinates).
  const Eigen::MatrixXcd left = solver.eigenvectors().inverse();
  const Eigen::MatrixXcd forcing = left * (model.b * hover.force_n.asDiagonal()).cast<std::complex<double>>();
  std::vector<ArmModeShape> modes;
  for (Eigen::Index i = 0; i < model.a.rows(); ++i) {
    const std::complex<double> lambda = solver.eigenvalues()(i);
    // One of each conjugate pair; the rigid body's (zero) eigenvalues skipped.
    if (lambda.imag() <= 0 || std::abs(lambda) < 1e-3) continue;
    ArmModeShape mode;
    mode.frequency_hz = std::abs(lambda) / (2.0 * M_PI);
    mode.damping_ratio = -lambda.real() / std::abs(lambda);
    const Eigen::VectorXcd b = solver.eigenvectors().col(i).segment(n - arms, arms);
    mode.deflection = RealShape(b);
    const double omega = std::abs(lambda);
    const double variance = b.cwiseAbs().maxCoeff() * b.cwiseAbs().maxCoeff() * forcing.row(i).squaredNorm() /
                            (2.0 * std::max(mode.damping_ratio, 1e-6) * omega * omega * omega);
    mode.turbulence_response = std::sqrt(variance);
    modes.push_back(mode);
  }
  std::sort(modes.begin(), modes.end(),
            [](const ArmModeShape& x, const ArmModeShape& y) { return x.frequency_hz < y.frequency_hz; });
  return modes;
}

Eigen::MatrixXd ModalGaugeWeights(const std::vector<ArmModeShape>& modes, int arm_count) {
  if (static_cast<int>(modes.size()) != arm_count || arm_count < 1) return Eigen::MatrixXd();
  Eigen::MatrixXd shapes(arm_count, arm_count);
  for (int m = 0; m < arm_count; ++m) shapes.col(m) = modes[static_cast<size_t>(m)].deflection;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(shapes);
  if (!(lu.rcond() >= 1e-6)) return Eigen::MatrixXd();
  return lu.inverse();
}

Eigen::MatrixXd GaugedModalWeights(const std::vector<ArmModeShape>& modes, const std::vector<bool>& gauged) {
  const int arms = static_cast<int>(gauged.size());
  std::vector<int> gauge_arms;
  for (int i = 0; i < arms; ++i) {
    if (gauged[static_cast<size_t>(i)]) gauge_arms.push_back(i);
  }
  const int gauges = static_cast<int>(gauge_arms.size());
  if (static_cast<int>(modes.size()) != arms || gauges == 0) return Eigen::MatrixXd();
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(arms, arms);
  for (int m = 0; m < arms; ++m) {
    // m first, then the others by their distance in frequency from m.
    std::vector<int> order(static_cast<size_t>(arms));
    for (int j = 0; j < arms; ++j) order[static_cast<size_t>(j)] = j;
    const double f_m = modes[static_cast<size_t>(m)].frequency_hz;
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      if (a == m || b == m) return a == m && b != m;
      return std::fabs(modes[static_cast<size_t>(a)].frequency_hz - f_m) <
             std::fabs(modes[static_cast<size_t>(b)].frequency_hz - f_m);
    });
    Eigen::MatrixXd shapes(gauges, gauges);  // rows: the gauged arms; columns: m and the nulled modes
    for (int c = 0; c < gauges; ++c) {
      const Eigen::VectorXd& deflection = modes[static_cast<size_t>(order[static_cast<size_t>(c)])].deflection;
      for (int r = 0; r < gauges; ++r) shapes(r, c) = deflection(gauge_arms[static_cast<size_t>(r)]);
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(shapes);
    if (!(lu.rcond() >= 1e-6)) continue;
    const Eigen::MatrixXd inverse = lu.inverse();  // row 0 reads m (column 0)
    for (int r = 0; r < gauges; ++r) weights(m, gauge_arms[static_cast<size_t>(r)]) = inverse(0, r);
  }
  return weights;
}

int MostReadableArmMode(const std::vector<ArmModeShape>& modes, const Eigen::MatrixXd& weights) {
  if (weights.rows() != static_cast<Eigen::Index>(modes.size()) || modes.empty()) return -1;
  int best = -1;  // stays -1 when every row is zero
  double best_ratio = -1;
  for (int m = 0; m < weights.rows(); ++m) {
    const double response = modes[static_cast<size_t>(m)].turbulence_response;
    const double norm2 = weights.row(m).squaredNorm();
    if (!(norm2 > 0)) continue;
    const double ratio = response * response / norm2;
    if (ratio > best_ratio) {
      best = m;
      best_ratio = ratio;
    }
  }
  return best;
}

bool ArmModeStandsAlone(const std::vector<ArmModeShape>& modes, int m, double band_fraction, double variance_ratio) {
  if (m < 0 || m >= static_cast<int>(modes.size())) return false;
  const ArmModeShape& mode = modes[static_cast<size_t>(m)];
  for (const ArmModeShape& other : modes) {
    if (!OtherInBand(mode, other, band_fraction)) continue;
    const double ratio =
        mode.turbulence_response * mode.turbulence_response / (other.turbulence_response * other.turbulence_response);
    if (!(ratio >= variance_ratio)) return false;
  }
  return true;
}

bool ArmModeLeakSmall(const std::vector<ArmModeShape>& modes, const Eigen::RowVectorXd& w, int m, double band_fraction,
                      double variance_ratio) {
  if (m < 0 || m >= static_cast<int>(modes.size())) return false;
  const ArmModeShape& mode = modes[static_cast<size_t>(m)];
  double leak = 0;  // variance of the other modes in the reading [1]
  for (const ArmModeShape& other : modes) {
    if (!OtherInBand(mode, other, band_fraction)) continue;
    const double through = w.dot(other.deflection) * other.turbulence_response;
    leak += through * through;
  }
  const double own = w.dot(mode.deflection) * mode.turbulence_response;
  return leak * variance_ratio < own * own;
}

}  // namespace birotor
