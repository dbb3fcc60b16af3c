// The parameter-augmented hover linearisation and its observability.
#include "model/parameter_observability.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "model/birotor_dynamics.h"
#include "model/equilibrium.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {

using AugVector = Eigen::Matrix<double, kParameterAugmentedSize, 1>;

enum ParameterIndex : int {
  kOmega1 = 10,
  kOmega2 = 11,
  kMu1 = 12,
  kMu2 = 13,
  kOffset1 = 14,
  kOffset2 = 15,
  kThetaK1 = 16,
  kThetaK2 = 17,
  kThetaBodyMass = 18,
  kThetaTipMass = 19,
  kThetaThrustCoeff = 20,
  kThetaMotorLag = 21,
  kThetaScale1 = 22,
  kThetaScale2 = 23,
};

// The hover point: equilibrium q, omega_i from the nominal map, mu = 1, o = 0, theta = 0.
struct HoverPoint {
  AugVector x;
  double command_rad_s[kBirotorRotors];  // held rotor speed commands (the hover speeds)
};

HoverPoint MakeHoverPoint(const BirotorParams& p) {
  const Equilibrium eq = SolveHoverEquilibrium(p);
  HoverPoint h;
  h.x.setZero();
  h.x(kB1) = eq.deflection_rad[0];
  h.x(kB2) = eq.deflection_rad[1];
  for (int i = 0; i < kBirotorRotors; ++i) {
    h.command_rad_s[i] = std::sqrt(eq.force_n[i] / p.thrust_coeff_n_s2_rad2);
    h.x(kOmega1 + i) = h.command_rad_s[i];
    h.x(kMu1 + i) = 1.0;
  }
  return h;
}

// The vehicle with the deviations theta applied (the per-arm stiffness
// deviations are applied by Acceleration, the gauge scales by the strain row).
BirotorParams Perturbed(const BirotorParams& p, const AugVector& x) {
  BirotorParams q = p;
  q.body_mass_kg *= 1.0 + x(kThetaBodyMass);
  q.tip_mass_kg *= 1.0 + x(kThetaTipMass);
  q.thrust_coeff_n_s2_rad2 *= 1.0 + x(kThetaThrustCoeff);
  q.motor_time_constant_s *= 1.0 + x(kThetaMotorLag);
  return q;
}

// q_ddot with f_i = mu_i c_T omega_i^2 and hinge i's stiffness k (1 + theta_ki).
Coords<double> Acceleration(const BirotorParams& p, const AugVector& x) {
  const BirotorParams q = Perturbed(p, x);
  const Coords<double> pos = x.head<kNumCoordinates>(), vel = x.segment<kNumCoordinates>(kNumCoordinates);
  double force_n[kBirotorRotors];
  for (int i = 0; i < kBirotorRotors; ++i)
    force_n[i] = x(kMu1 + i) * q.thrust_coeff_n_s2_rad2 * x(kOmega1 + i) * x(kOmega1 + i);
  const DynamicsTerms<double> t = ComputeDynamicsTerms(q, pos, vel, force_n[0], force_n[1]);
  Coords<double> rhs = t.generalized_thrust - t.coriolis - t.gravity_spring;
  rhs(kB1) -= p.arm_stiffness_n_m_rad * x(kThetaK1) * pos(kB1);
  rhs(kB2) -= p.arm_stiffness_n_m_rad * x(kThetaK2) * pos(kB2);
  return SolveMassMatrix<double>(t.mass, rhs);
}

AugVector Derivative(const BirotorParams& p, const HoverPoint& h, const AugVector& x) {
  AugVector dx = AugVector::Zero();  // mu_i, o_i and theta: constants
  dx.head<kNumCoordinates>() = x.segment<kNumCoordinates>(kNumCoordinates);
  dx.segment<kNumCoordinates>(kNumCoordinates) = Acceleration(p, x);
  const double tau_s = p.motor_time_constant_s * (1.0 + x(kThetaMotorLag));
  for (int i = 0; i < kBirotorRotors; ++i) dx(kOmega1 + i) = (h.command_rad_s[i] - x(kOmega1 + i)) / tau_s;
  return dx;
}

// |b_i| at the hover equilibrium [rad].
double HoverDeflectionRad(const BirotorParams& p, int arm) {
  return std::fabs(SolveHoverEquilibrium(p).deflection_rad[arm]);
}

// The rows of one measurement at x.
Eigen::VectorXd Measure(const BirotorParams& p, ParameterMeasurement m, const AugVector& x) {
  switch (m) {
    case ParameterMeasurement::kStrain:
      // o_i in units of the hover deflection |b_i0| (comparable with theta_si).
      return Eigen::Vector2d((1.0 + x(kThetaScale1)) * x(kB1) + x(kOffset1) * HoverDeflectionRad(p, 0),
                             (1.0 + x(kThetaScale2)) * x(kB2) + x(kOffset2) * HoverDeflectionRad(p, 1));
    case ParameterMeasurement::kTelemetry:
      return Eigen::Vector2d(x(kOmega1), x(kOmega2));
    case ParameterMeasurement::kGyro:
      return Eigen::VectorXd::Constant(1, x(kNumCoordinates + kPhi));
    case ParameterMeasurement::kAccelerometer: {
      // Specific force along body z: R(phi)^T (a - g), a = (x_ddot, z_ddot).
      const Coords<double> acc = Acceleration(p, x);
      const double phi = x(kPhi);
      return Eigen::VectorXd::Constant(1, -std::sin(phi) * acc(kX) + std::cos(phi) * (acc(kZ) + p.gravity_m_s2));
    }
  }
  return Eigen::VectorXd();
}

// Central-difference step of state j: relative to its scale.
double Step(const AugVector& x, int j) { return 1e-6 * std::max(1.0, std::fabs(x(j))) * (j < kOmega1 ? 1e-2 : 1.0); }

}  // namespace

const std::vector<std::string>& ParameterAugmentedStateNames() {
  static const std::vector<std::string> names = {
      "x",   "z",   "phi", "b1", "b2", "x_dot", "z_dot", "phi_dot", "b1_dot", "b2_dot", "omega1", "omega2",
      "mu1", "mu2", "o1",  "o2", "k1", "k2",    "m",     "m_p",     "c_T",    "tau_m",  "s1",     "s2"};
  return names;
}

void LinearizeWithParameters(const BirotorParams& params, const std::vector<ParameterMeasurement>& measured,
                             Eigen::MatrixXd* a, Eigen::MatrixXd* c) {
  const HoverPoint h = MakeHoverPoint(params);
  const int n = kParameterAugmentedSize;
  int rows = 0;
  for (ParameterMeasurement m : measured) rows += static_cast<int>(Measure(params, m, h.x).size());
  a->setZero(n, n);
  c->setZero(rows, n);
  for (int j = 0; j < n; ++j) {
    const double step = Step(h.x, j);
    AugVector plus = h.x, minus = h.x;
    plus(j) += step;
    minus(j) -= step;
    a->col(j) = (Derivative(params, h, plus) - Derivative(params, h, minus)) / (2.0 * step);
    int row = 0;
    for (ParameterMeasurement m : measured) {
      const Eigen::VectorXd d = (Measure(params, m, plus) - Measure(params, m, minus)) / (2.0 * step);
      c->block(row, j, d.size(), 1) = d;
      row += static_cast<int>(d.size());
    }
  }
}

ParameterObservability AnalyzeParameterObservability(const BirotorParams& params,
                                                     const std::vector<ParameterMeasurement>& measured) {
  Eigen::MatrixXd a, c;
  LinearizeWithParameters(params, measured, &a, &c);
  const std::vector<std::string>& names = ParameterAugmentedStateNames();
  ParameterObservability out;
  out.report = AnalyzeObservability(a, c, names);
  const Eigen::MatrixXd& hidden = out.report.hidden_basis;
  for (int j = kMu1; j < kParameterAugmentedSize; ++j) {
    const double component = hidden.cols() > 0 ? hidden.row(j).norm() : 0.0;
    if (component < 1e-6) out.observable_parameters.push_back(names[j]);
  }
  // Determined functionals: the null space of the hidden block's transpose.
  const int slow = kParameterAugmentedSize - kMu1;
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(slow, std::max<Eigen::Index>(hidden.cols(), 1));
  if (hidden.cols() > 0) block = hidden.middleRows(kMu1, slow);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(block.transpose(), Eigen::ComputeFullV);
  int rank = 0;
  for (int k = 0; k < svd.singularValues().size(); ++k)
    if (svd.singularValues()(k) > 1e-6) ++rank;
  out.determined = slow - rank;
  // Reduced row echelon form of the determined functionals (pivot 1 on the
  // first free axis in the order mu1 .. s2), so each reads as "pivot = ...".
  Eigen::MatrixXd rows = svd.matrixV().rightCols(out.determined).transpose();
  int pivot_row = 0;
  for (int col = 0; col < slow && pivot_row < rows.rows(); ++col) {
    Eigen::Index best;
    if (rows.col(col).tail(rows.rows() - pivot_row).cwiseAbs().maxCoeff(&best) < 1e-6) continue;
    rows.row(pivot_row).swap(rows.row(pivot_row + best));
    const double pivot = rows(pivot_row, col);  // copies: the rows change below
    rows.row(pivot_row) /= pivot;
    for (int r = 0; r < rows.rows(); ++r) {
      const double factor = rows(r, col);
      if (r != pivot_row) rows.row(r) -= factor * rows.row(pivot_row);
    }
    ++pivot_row;
  }
  for (int r = 0; r < rows.rows(); ++r) {
    std::string text;
    for (int k = 0; k < slow; ++k) {
      if (std::fabs(rows(r, k)) < 0.05) continue;
      char term[48];
      std::snprintf(term, sizeof(term), "%s%.2f %s", text.empty() ? "" : " + ", rows(r, k), names[kMu1 + k].c_str());
      text += term;
    }
    out.determined_combinations.push_back(text);
  }
  return out;
}

}  // namespace birotor
