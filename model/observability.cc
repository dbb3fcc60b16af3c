#include "model/observability.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace birotor {
namespace {

// Relative tolerance for "zero" singular values of the scaled matrices, whose
// entries are O(1) after balancing and time scaling.
constexpr double kRankTolerance = 1e-8;

// Diagonal balancing D (A -> D^-1 A D) with powers of two, so that each row
// and column of the off-diagonal part has similar norm (Parlett-Reinsch).
Eigen::VectorXd BalancingScale(const Eigen::MatrixXd& a) {
  const int n = static_cast<int>(a.rows());
  Eigen::VectorXd d = Eigen::VectorXd::Ones(n);
  Eigen::MatrixXd m = a;
  bool changed = true;
  for (int sweep = 0; changed && sweep < 100; ++sweep) {
    changed = false;
    for (int i = 0; i < n; ++i) {
      double col = 0, row = 0;
      for (int j = 0; j < n; ++j) {
        if (j == i) continue;
        col += std::abs(m(j, i));
        row += std::abs(m(i, j));
      }
      if (col == 0 || row == 0) continue;
      double f = 1.0;
      const double s = col + row;
      while (col < row / 2.0) {
        col *= 2.0;
        row /= 2.0;
        f *= 2.0;
      }
      while (col >= row * 2.0) {
        col /= 2.0;
        row *= 2.0;
        f /= 2.0;
      }
      if ((col + row) < 0.95 * s) {
        changed = true;
        d(i) *= f;
        m.col(i) *= f;
        m.row(i) /= f;
      }
    }
  }
  return d;
}

// Orthonormal basis of the null space of m (columns), by SVD.
Eigen::MatrixXd NullSpace(const Eigen::MatrixXd& m, double scale) {
  const int cols = static_cast<int>(m.cols());
  if (m.rows() == 0) return Eigen::MatrixXd::Identity(cols, cols);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  int rank = 0;
  for (int i = 0; i < s.size(); ++i)
    if (s(i) > kRankTolerance * std::max(1.0, scale)) ++rank;
  return svd.matrixV().rightCols(cols - rank);
}

SubspaceReport Analyze(const Eigen::MatrixXd& a, const Eigen::MatrixXd& c, const std::vector<std::string>& names) {
  const int n = static_cast<int>(a.rows());
  SubspaceReport report;
  report.state_size = n;

  // Scaled system: A_s = D^-1 A D T, C_s = C D normalised row-wise.
  const Eigen::VectorXd d = BalancingScale(a);
  Eigen::MatrixXd as = d.cwiseInverse().asDiagonal() * a * d.asDiagonal();
  const double radius = std::max(1e-12, as.eigenvalues().cwiseAbs().maxCoeff());
  report.time_scale_s = 1.0 / radius;
  as /= radius;
  Eigen::MatrixXd cs = c * d.asDiagonal();
  for (int r = 0; r < cs.rows(); ++r) {
    const double norm = cs.row(r).norm();
    if (norm > 0) cs.row(r) /= norm;
  }

  // Staircase recursion for the unobservable subspace.
  Eigen::MatrixXd basis = NullSpace(cs, 1.0);
  while (basis.cols() > 0) {
    const Eigen::MatrixXd leak = (Eigen::MatrixXd::Identity(n, n) - basis * basis.transpose()) * as * basis;
    const Eigen::MatrixXd keep = NullSpace(leak, 1.0);
    if (keep.cols() == basis.cols()) break;
    basis = basis * keep;
  }
  report.rank = n - static_cast<int>(basis.cols());

  // Back to original coordinates: x = D x_s.
  Eigen::MatrixXd hidden = d.asDiagonal() * basis;
  if (hidden.cols() > 0)
    hidden = Eigen::HouseholderQR<Eigen::MatrixXd>(hidden).householderQ() * Eigen::MatrixXd::Identity(n, hidden.cols());
  report.hidden_basis = hidden;
  for (int j = 0; j < n; ++j) {
    if (basis.cols() == 0) break;
    // Axis j is hidden if it lies in span(basis) (scaled axes are the same axes).
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(n, j);
    if ((e - basis * (basis.transpose() * e)).norm() < 1e-6) report.hidden_states.push_back(names.at(j));
  }

  // Singular values of the scaled observability matrix [C; CA; ...; CA^{n-1}].
  const int m = static_cast<int>(cs.rows());
  Eigen::MatrixXd obs(m * n, n);
  Eigen::MatrixXd block = cs;
  for (int k = 0; k < n; ++k) {
    obs.middleRows(k * m, m) = block;
    block = block * as;
  }
  report.singular_values = Eigen::JacobiSVD<Eigen::MatrixXd>(obs).singularValues();

  // PBH margins: sigma_min([A_s - lambda I; C_s]) for each eigenvalue.
  const Eigen::VectorXcd lambdas = as.eigenvalues();
  report.pbh_margins.resize(n);
  for (int i = 0; i < n; ++i) {
    Eigen::MatrixXcd pbh(n + m, n);
    pbh.topRows(n) = as.cast<std::complex<double>>() - lambdas(i) * Eigen::MatrixXcd::Identity(n, n);
    pbh.bottomRows(m) = cs.cast<std::complex<double>>();
    report.pbh_margins(i) = Eigen::JacobiSVD<Eigen::MatrixXcd>(pbh).singularValues().minCoeff();
  }
  return report;
}

}  // namespace

SubspaceReport AnalyzeObservability(const Eigen::MatrixXd& a, const Eigen::MatrixXd& c,
                                    const std::vector<std::string>& state_names) {
  return Analyze(a, c, state_names);
}

SubspaceReport AnalyzeControllability(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                                      const std::vector<std::string>& state_names) {
  return Analyze(a.transpose(), b.transpose(), state_names);
}

bool SelectionMatrix(const std::vector<std::string>& state_names, const std::vector<std::string>& measured,
                     Eigen::MatrixXd* c, std::string* unknown) {
  c->setZero(static_cast<int>(measured.size()), static_cast<int>(state_names.size()));
  for (size_t r = 0; r < measured.size(); ++r) {
    const auto it = std::find(state_names.begin(), state_names.end(), measured[r]);
    if (it == state_names.end()) {
      *unknown = measured[r];
      return false;
    }
    (*c)(static_cast<int>(r), static_cast<int>(it - state_names.begin())) = 1.0;
  }
  return true;
}

}  // namespace birotor
