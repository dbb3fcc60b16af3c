#include "identification/free_arm_window_cost.h"

#include <ceres/dynamic_autodiff_cost_function.h>
#include <ceres/jet.h>

#include <Eigen/Core>
#include <algorithm>
#include <utility>

#include "model/rk4.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {

// Columns of the sensitivities: the parameter blocks of the window in order.
enum Column : int { kColK = 0, kColD = 1, kColThrust = 2, kColTipMass = 3, kColState = 4, kColKnots = 9 };
// The local point a stage is linearised at: x, then the inputs u = (k, d, m_p, f1, f2).
enum Input : int { kInK = 0, kInD = 1, kInTipMass = 2, kInForce1 = 3, kInForce2 = 4 };
constexpr int kInputs = 5;
constexpr int kLocal = kFreeArmStateSize + kInputs;
using Jet = ceres::Jet<double, kLocal>;
constexpr int kMaxColumns = FreeArmWindowCost::kMaxParameters;

// [x | S]: the state and its sensitivities to the P parameters (5 x (1 + P)).
using Augmented =
    Eigen::Matrix<double, kFreeArmStateSize, Eigen::Dynamic, Eigen::RowMajor, kFreeArmStateSize, 1 + kMaxColumns>;
// d u / d theta (5 x P).
using InputSensitivity = Eigen::Matrix<double, kInputs, Eigen::Dynamic, Eigen::RowMajor, kInputs, kMaxColumns>;
// d mu_i / d theta of one rotor's relative thrust mu_i = 1 + eta_i (1 x P).
using Row = Eigen::Matrix<double, 1, Eigen::Dynamic, Eigen::RowMajor, 1, kMaxColumns>;
// d r / d theta of one sample's residuals.
using ResidualSensitivity = Eigen::Matrix<double, kFreeArmResidualsPerSample, Eigen::Dynamic, Eigen::RowMajor,
                                          kFreeArmResidualsPerSample, kMaxColumns>;

// The local Jets at (x, u): each variable its own derivative direction.
struct LocalPoint {
  FreeArmState<Jet> x;
  Jet u[kInputs];
  LocalPoint(const Augmented& z, const double (&inputs)[kInputs]) {
    for (int i = 0; i < kFreeArmStateSize; ++i) x(i) = Jet(z(i, 0), i);
    for (int i = 0; i < kInputs; ++i) u[i] = Jet(inputs[i], kFreeArmStateSize + i);
  }
};

// x_dot = f(x, u) on the local Jets: its value and d x_dot / d(x, u). Flattened
// (every call inlined): GCC otherwise calls out for each Jet operation,
// which took half of the evaluation.
[[gnu::flatten]] FreeArmState<Jet> LocalDerivative(const BirotorParams& known, const LocalPoint& p) {
  return FreeArmDerivative<Jet>(known, p.u[kInK], p.u[kInD], p.u[kInTipMass], p.x, p.u[kInForce1], p.u[kInForce2]);
}

// The residuals of sample j on the local Jets (flattened as above).
[[gnu::flatten]] void LocalResiduals(const FreeArmWindowResidual& w, size_t j, const LocalPoint& p, Jet* r) {
  w.SampleResiduals<Jet>(j, p.x, p.u[kInK], p.u[kInD], p.u[kInTipMass], p.u[kInForce1], p.u[kInForce2], r);
}

// d y / d theta = d y / d x S + d y / d u U for a Jet y over (x, u), into row `row` of *out.
template <class Out>
void ChainRow(const Jet& y, const Augmented& z, const InputSensitivity& du, int row, Out* out) {
  const int p = static_cast<int>(du.cols());
  auto target = out->row(row);
  target.setZero();
  for (int i = 0; i < kFreeArmStateSize; ++i) {
    if (y.v[i] != 0.0) target += y.v[i] * z.row(i).segment(1, p);
  }
  for (int i = 0; i < kInputs; ++i) {
    if (y.v[kFreeArmStateSize + i] != 0.0) target += y.v[kFreeArmStateSize + i] * du.row(i);
  }
}

// Relative thrust mu = 1 + eta of `rotor` at sample j and its knot row.
double Mu(const FreeArmWindowResidual& w, const double* knots, int rotor, size_t j, Row* d_mu) {
  d_mu->setZero();
  if (knots == nullptr) return 1.0;
  const int n = w.num_knots(), s = w.KnotSegment(j);
  const double weight = w.KnotWeight(j);
  const double* k = knots + rotor * n;
  (*d_mu)(kColKnots + rotor * n + s) = 1.0 - weight;
  (*d_mu)(kColKnots + rotor * n + s + 1) += weight;
  return 1.0 + (k[s] + weight * (k[s + 1] - k[s]));
}

// The rows of sample j into Ceres' row-major blocks (k, d, c_T, m_p ratios,
// x_0, knots; a null block is held constant).
void WriteJacobianRows(const ResidualSensitivity& dr, size_t j, int knot_block_size, double** jacobians) {
  const int block_sizes[6] = {1, 1, 1, 1, kFreeArmStateSize, knot_block_size};
  int column = 0;
  for (int b = 0; b < (knot_block_size > 0 ? 6 : 5); column += block_sizes[b], ++b) {
    if (jacobians[b] == nullptr) continue;
    for (int i = 0; i < kFreeArmResidualsPerSample; ++i) {
      double* out = jacobians[b] + (kFreeArmResidualsPerSample * j + i) * block_sizes[b];
      for (int c = 0; c < block_sizes[b]; ++c) out[c] = dr(i, column + c);
    }
  }
}

}  // namespace

ceres::CostFunction* FreeArmWindowCost::Create(const BirotorParams& known,
                                               std::vector<FreeArmWindowResidual::Sample> samples,
                                               const FreeArmWindowResidual::Noise& noise, int substeps,
                                               const FreeArmWindowResidual::Scales& scales, double turbulence_knot_s,
                                               const FreeArmWindowResidual** functor) {
  auto residual =
      std::make_unique<FreeArmWindowResidual>(known, std::move(samples), noise, substeps, scales, turbulence_knot_s);
  if (kColKnots + residual->KnotBlockSize() > kMaxParameters) {
    return FreeArmWindowResidual::CreateAutoDiff(known, residual->samples(), noise, substeps, scales, turbulence_knot_s,
                                                 functor);
  }
  if (functor != nullptr) *functor = residual.get();
  return new FreeArmWindowCost(std::move(residual));
}

FreeArmWindowCost::FreeArmWindowCost(std::unique_ptr<const FreeArmWindowResidual> residual)
    : residual_(std::move(residual)) {
  for (int ratio = 0; ratio < 4; ++ratio) mutable_parameter_block_sizes()->push_back(1);
  mutable_parameter_block_sizes()->push_back(kFreeArmStateSize);
  if (residual_->num_knots() > 0) mutable_parameter_block_sizes()->push_back(residual_->KnotBlockSize());
  set_num_residuals(kFreeArmResidualsPerSample * static_cast<int>(residual_->samples().size()));
}

// x and S = dx / dtheta from S_0 = dx_0 / dtheta by RK4 over the augmented
// state: a stage's derivative is [f(x, u) | f_x S + f_u U], the forward-mode
// derivative of the functor's own step (same forces, interpolated as there).
bool FreeArmWindowCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const FreeArmWindowResidual& w = *residual_;
  if (jacobians == nullptr) return w(parameters, residuals);
  const std::vector<FreeArmWindowResidual::Sample>& samples = w.samples();
  const FreeArmWindowResidual::Scales& scales = w.scales();
  const double* knots = w.num_knots() > 0 ? parameters[5] : nullptr;
  const int p = kColKnots + w.KnotBlockSize();
  const double c_t = parameters[2][0] * scales.thrust_coeff_n_s2_rad2;
  double inputs[kInputs] = {parameters[0][0] * scales.stiffness_n_m_rad, parameters[1][0] * scales.damping_n_m_s_rad,
                            parameters[3][0] * scales.tip_mass_kg, 0.0, 0.0};
  InputSensitivity du = InputSensitivity::Zero(kInputs, p);
  du(kInK, kColK) = scales.stiffness_n_m_rad;
  du(kInD, kColD) = scales.damping_n_m_s_rad;
  du(kInTipMass, kColTipMass) = scales.tip_mass_kg;
  Augmented z = Augmented::Zero(kFreeArmStateSize, 1 + p);
  for (int i = 0; i < kFreeArmStateSize; ++i) {
    z(i, 0) = parameters[4][i];
    z(i, 1 + kColState + i) = 1.0;
  }
  // f_i = c_T omega_i^2 mu_i with omega and mu linear between samples a, b
  // (the functor's expressions, so the values are its own).
  double mu_prev[kBirotorRotors], mu_next[kBirotorRotors];
  Row d_mu_prev[kBirotorRotors] = {Row::Zero(p), Row::Zero(p)},
      d_mu_next[kBirotorRotors] = {Row::Zero(p), Row::Zero(p)};
  for (int rotor = 0; rotor < kBirotorRotors; ++rotor) mu_next[rotor] = Mu(w, knots, rotor, 0, &d_mu_next[rotor]);
  auto set_force = [&](int rotor, double omega, double mu, const Row& d_mu, double* input, InputSensitivity* d) {
    auto row = d->row(kInForce1 + rotor);
    row = (c_t * (omega * omega)) * d_mu;
    row(kColThrust) += scales.thrust_coeff_n_s2_rad2 * (omega * omega) * mu;
    input[kInForce1 + rotor] = c_t * (omega * omega) * mu;
  };
  auto stage_force = [&](const FreeArmWindowResidual::Sample& a, const FreeArmWindowResidual::Sample& b, int rotor,
                         double alpha, double* input, InputSensitivity* d) {
    const double omega = a.omega_rad_s[rotor] + alpha * (b.omega_rad_s[rotor] - a.omega_rad_s[rotor]);
    const double mu = mu_prev[rotor] + alpha * (mu_next[rotor] - mu_prev[rotor]);
    set_force(rotor, omega, mu, (1.0 - alpha) * d_mu_prev[rotor] + alpha * d_mu_next[rotor], input, d);
  };
  double stage_inputs[3][kInputs];
  InputSensitivity stage_du[3] = {du, du, du};
  ResidualSensitivity dr(kFreeArmResidualsPerSample, p);
  const int substeps = w.substeps();
  for (size_t j = 0; j < samples.size(); ++j) {
    for (int rotor = 0; rotor < kBirotorRotors; ++rotor) {
      mu_prev[rotor] = mu_next[rotor];
      d_mu_prev[rotor] = d_mu_next[rotor];
      if (j > 0) mu_next[rotor] = Mu(w, knots, rotor, j, &d_mu_next[rotor]);
    }
    if (j > 0) {
      const FreeArmWindowResidual::Sample& s0 = samples[j - 1];
      const FreeArmWindowResidual::Sample& s1 = samples[j];
      const double h = s0.dt_s / substeps;
      for (int s = 0; s < substeps; ++s) {
        const double a0 = static_cast<double>(s) / substeps;
        const double a1 = static_cast<double>(s + 1) / substeps;
        const double alphas[3] = {a0, 0.5 * (a0 + a1), a1};  // Rk4Stage order: start, middle, end
        for (int at = 0; at < 3; ++at) {
          std::copy(inputs, inputs + kInputs, stage_inputs[at]);
          for (int rotor = 0; rotor < kBirotorRotors; ++rotor) {
            stage_force(s0, s1, rotor, alphas[at], stage_inputs[at], &stage_du[at]);
          }
        }
        z = Rk4Step(z, h, [&](const Augmented& y, Rk4Stage stage) {
          const int at = static_cast<int>(stage);
          const LocalPoint local(y, stage_inputs[at]);
          const FreeArmState<Jet> x_dot = LocalDerivative(w.known(), local);
          Augmented dz(kFreeArmStateSize, 1 + p);
          for (int i = 0; i < kFreeArmStateSize; ++i) {
            dz(i, 0) = x_dot(i).a;
            auto row = dz.row(i).segment(1, p);
            ChainRow(x_dot(i), y, stage_du[at], 0, &row);
          }
          return dz;
        });
      }
    }
    // Residuals at sample j (forces at alpha = 1 of the last interval, or mu at j = 0).
    const FreeArmWindowResidual::Sample& m = samples[j];
    for (int rotor = 0; rotor < kBirotorRotors; ++rotor) {
      set_force(rotor, m.omega_rad_s[rotor], mu_next[rotor], d_mu_next[rotor], inputs, &du);
    }
    const LocalPoint local(z, inputs);
    Jet r[kFreeArmResidualsPerSample];
    LocalResiduals(w, j, local, r);
    for (int i = 0; i < kFreeArmResidualsPerSample; ++i) {
      residuals[kFreeArmResidualsPerSample * j + i] = r[i].a;
      ChainRow(r[i], z, du, i, &dr);
    }
    WriteJacobianRows(dr, j, w.KnotBlockSize(), jacobians);
  }
  return true;
}

}  // namespace birotor
