// State, process model and measurement models of the rotor-force EKF for a
// vehicle with N elastic arms (model/vehicle_description.h, N = 2 .. kMaxArms),
// templated on N so that every vector and matrix is fixed-size (no heap in the
// per-sample path). docs/estimator.md, "The EKF for N arms".
#pragma once

#include <ceres/jet.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <array>

#include "estimator/kalman_fusion.h"
#include "estimator/multi_arm_ekf_jets.h"
#include "model/multi_arm_dynamics.h"
#include "model/rk4.h"
#include "model/vehicle_description.h"

namespace birotor {

// Named indices of the N-arm filter state
//   x = [e_1..e_N, b_1..b_N, phi_dot, b_dot_1..b_dot_N, omega_1..omega_N, mu_1..mu_N]
// e_i [rad] (offset of calibrated gauge i, in deflection), b_i [rad],
// phi_dot [rad/s], b_dot_i [rad/s], omega_i [rad/s], mu_i [1]
// (f_i = mu_i c_T,i omega_i^2). The offsets are random walks; the last
// kDynamicSize states (from kFirstDynamic) have dynamics, so the transition
// is [I, 0; 0, Phi_d]. The order puts what the strain gauges read (e_i, b_i)
// first: the strain fusion, every sample, works on the leading 2N states
// (LeadingStates, kalman_fusion.h) and reaches the rest through their cross
// covariance; the gyro reads the leading 2N + 1, the telemetry all but mu_i.
template <int N>
struct MultiArmEkfLayout {
  static_assert(N >= 2 && N <= kMaxArms, "2 .. kMaxArms arms");
  static constexpr int kArms = N;
  static constexpr int GaugeOffset(int arm) { return arm; }
  static constexpr int Deflection(int arm) { return N + arm; }
  static constexpr int kPitchRate = 2 * N;
  static constexpr int DeflectionRate(int arm) { return 2 * N + 1 + arm; }
  static constexpr int Omega(int arm) { return 3 * N + 1 + arm; }
  static constexpr int ThrustScale(int arm) { return 4 * N + 1 + arm; }
  static constexpr int kFirstDynamic = N;
  static constexpr int kDynamicSize = 1 + 4 * N;
  static constexpr int kStateSize = 1 + 5 * N;
  static constexpr int kStrainStates = 2 * N;  // e_i, b_i: what the strain reads
  // Index of a dynamic state in A_d, Phi_d (the block from kFirstDynamic).
  static constexpr int Dynamic(int state) { return state - kFirstDynamic; }
  // Jet variables of the process Jacobian: b_i, phi_dot, b_dot_i (the first
  // 1 + 2N dynamic states, same order), then f_i.
  static constexpr int kJetSize = 1 + 3 * N;
  static constexpr int JetForce(int arm) { return 1 + 2 * N + arm; }
};

// M = L D L^T of the symmetric positive definite n x n mass matrix (unit
// lower-triangular L, no pivoting, no square roots: the factorisation of
// SolveMultiArmMassMatrix in model/multi_arm_dynamics.h) at a compile-time n,
// factored once and solved for any number of right-hand sides: the process
// Jacobian solves its value and its 1 + 3N derivative columns with one factor.
// Doubles only (a Jet's zero test would drop derivative parts, see there).
template <int n>
class MassMatrixLdlt {
 public:
  explicit MassMatrixLdlt(const Eigen::Matrix<double, n, n>& mass) {
    lower_.setIdentity();
    for (int j = 0; j < n; ++j) {
      diagonal_(j) = mass(j, j);
      for (int k = 0; k < j; ++k) diagonal_(j) -= lower_(j, k) * lower_(j, k) * diagonal_(k);
      for (int i = j + 1; i < n; ++i) {
        double sum = mass(i, j);
        for (int k = 0; k < j; ++k) sum -= lower_(i, k) * lower_(j, k) * diagonal_(k);
        lower_(i, j) = sum / diagonal_(j);
      }
    }
  }
  // x = M^-1 rhs, column by column: L y = rhs, then D L^T x = y. x's storage
  // order is free: a row-major x makes each row operation one contiguous run.
  template <int C, int Options>
  void SolveInPlace(Eigen::Matrix<double, n, C, Options>* x) const {
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < i; ++k) x->row(i) -= lower_(i, k) * x->row(k);
    }
    for (int i = n - 1; i >= 0; --i) {
      x->row(i) /= diagonal_(i);
      for (int k = i + 1; k < n; ++k) x->row(i) -= lower_(k, i) * x->row(k);
    }
  }

 private:
  Eigen::Matrix<double, n, n> lower_;
  Eigen::Matrix<double, n, 1> diagonal_;
};

// Arm i's directions (ArmDirections, model/multi_arm_dynamics.h) on a level
// body, phi = 0, where a_i = b_i (every evaluation of the filter's process
// model is there): from sin b_i and cos b_i alone by the angle sums
//   r_i = [cos b ca - sin b sa, sin b ca + cos b sa],
//   n_i = [-(sin b ct + cos b st), cos b ct - sin b st],
// ca, sa = cos, sin alpha_i and ct, st = cos, sin theta_i fixed per arm: one
// sincos per arm instead of MultiArmDirections' two sin/cos pairs (equal to
// it to rounding, tests/estimator/multi_arm_ekf_model_test.cc to 1e-15), and
// the lever l_i computed once instead of at every evaluation.
template <int N>
class LevelArmDirections {
 public:
  explicit LevelArmDirections(const VehicleDescription& vehicle) {
    for (int i = 0; i < N; ++i) {
      const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
      angles_[static_cast<size_t>(i)] = {std::cos(arm.angle_rad), std::sin(arm.angle_rad),
                                         std::cos(arm.thrust_angle_rad), std::sin(arm.thrust_angle_rad),
                                         arm.ThrustLeverM()};
    }
  }
  // T: double or a ceres Jet (SinCos, multi_arm_ekf_jets.h).
  template <typename T>
  ArmDirections<T> At(int arm, const T& b) const {
    const Angles& k = angles_[static_cast<size_t>(arm)];
    T s, c;
    SinCos(b, &s, &c);
    return {c * k.cos_arm - s * k.sin_arm, s * k.cos_arm + c * k.sin_arm, -(s * k.cos_thrust + c * k.sin_thrust),
            c * k.cos_thrust - s * k.sin_thrust, k.lever_m};
  }

 private:
  struct Angles {
    double cos_arm, sin_arm, cos_thrust, sin_thrust;  // of alpha_i and theta_i
    double lever_m;                                   // l_i [m], computed once
  };
  std::array<Angles, N> angles_{};
};

// Clamped rotor speed commands held over one prediction interval [rad/s].
template <int N>
struct MultiArmEkfInput {
  std::array<double, N> omega_cmd_rad_s{};
  bool supported = false;  // the ground holds the body: the supported model (multi_arm_ekf_supported.h)
};

// The accelerometer's model linearised where the process was: the specific
// force at the body centre in the body frame, (a_x, a_z) [m/s^2], a
// by-product of the process Jacobian (the x and z rows of the same solve).
template <int N>
struct MultiArmAccelLinearization {
  using Layout = MultiArmEkfLayout<N>;
  Eigen::Matrix<double, Layout::kStateSize, 1> x0 = Eigen::Matrix<double, Layout::kStateSize, 1>::Zero();
  Eigen::Vector2d value = Eigen::Vector2d::Zero();         // (a_x, a_z)(x0)
  Eigen::Matrix<double, 2, Layout::kStateSize> jacobian =  // d (a_x, a_z) / dx
      Eigen::Matrix<double, 2, Layout::kStateSize>::Zero();
};

// Process model x_dot = f(x, u) of a free body:
//   (phi_ddot, b_ddot_i) = the phi and b_i rows of MultiArmAcceleration
//   (model/multi_arm_dynamics.h) at phi = 0, x = z = 0, body velocity 0: for a
//   free body in uniform gravity they depend on none of x, z, phi, x_dot,
//   z_dot (tests/estimator/multi_arm_ekf_model_test.cc, to 1e-12);
//   b_dot_i from the state; f_i = mu_i c_T,i omega_i^2;
//   omega_i_dot = (clamp(cmd_i, 0, omega_max) - omega_i) / tau_m,i;
//   mu_i_dot = 0, e_i_dot = 0 (random walks, driven by process noise).
// With u.supported (on the ground) the held body's rows instead:
// phi_ddot = 0 and each arm's supported row (estimator/multi_arm_ekf_supported.h).
template <int N>
class MultiArmEkfModel {
 public:
  using Layout = MultiArmEkfLayout<N>;
  static constexpr int kS = Layout::kStateSize;
  static constexpr int kD = Layout::kDynamicSize;
  using State = Eigen::Matrix<double, kS, 1>;
  using Covariance = Eigen::Matrix<double, kS, kS>;
  using DynamicMatrix = Eigen::Matrix<double, kD, kD>;
  using Input = MultiArmEkfInput<N>;

  explicit MultiArmEkfModel(const VehicleDescription& vehicle)
      : vehicle_(vehicle), file_vehicle_(vehicle), directions_(vehicle) {}

  // Every arm's m_p,i = ratio m_p,i of the description (a learned tip mass).
  void SetTipMassScale(double ratio) {
    for (int i = 0; i < N; ++i) {
      const size_t k = static_cast<size_t>(i);
      vehicle_.arms[k].tip_mass_kg = ratio * file_vehicle_.arms[k].tip_mass_kg;
    }
  }

  const VehicleDescription& vehicle() const { return vehicle_; }
  // f_i = mu_i c_T,i omega_i^2 [N].
  double Force(const State& x, int arm) const {
    const double omega = x(Layout::Omega(arm));
    return x(Layout::ThrustScale(arm)) * ThrustCoeff(arm) * omega * omega;
  }
  // (df_i/domega_i, df_i/dmu_i).
  Eigen::Vector2d ForceGradient(const State& x, int arm) const {
    const double omega = x(Layout::Omega(arm)), c_t = ThrustCoeff(arm);
    return Eigen::Vector2d(2.0 * x(Layout::ThrustScale(arm)) * c_t * omega, c_t * omega * omega);
  }
  // The command as the motor sees it: clamp(cmd, 0, omega_max) [rad/s].
  double ClampCommand(double omega_cmd_rad_s) const {
    return std::clamp(omega_cmd_rad_s, 0.0, vehicle_.omega_max_rad_s);
  }

  State Derivative(const State& x, const Input& u) const;
  // A_d = df/dx on the dynamic block (indices Layout::Dynamic), exact: Ceres
  // Jets over (b_i, phi_dot, b_dot_i, f_i) through MultiArmAcceleration, then the chain rule
  // df_i/domega_i = 2 mu_i c_T,i omega_i, df_i/dmu_i = c_T,i omega_i^2.
  // With accel non-null also the specific force (a_x, a_z) = (x_ddot,
  // z_ddot + g) at phi = 0 and its gradient (the same solve). With x_dot
  // non-null also f(x, u) itself (the same solve: RK4's first stage).
  DynamicMatrix Jacobian(const State& x, const Input& u, MultiArmAccelLinearization<N>* accel = nullptr,
                         State* x_dot = nullptr) const;
  // One RK4 step over dt_s with u held.
  State Step(const State& x, const Input& u, double dt_s) const {
    return Rk4Step(x, dt_s, [&](const State& s) { return Derivative(s, u); });
  }
  // The same step when its first stage k1 = f(x, u) is known (from Jacobian).
  State StepFrom(const State& x, const State& k1, const Input& u, double dt_s) const {
    return Rk4StepFrom(x, k1, dt_s, [&](const State& s) { return Derivative(s, u); });
  }
  // Phi_d = exp(A_d dt) to fourth order, as EkfProcessModel::Transition:
  //   I + A dt (I + A dt/2 (I + A dt/3 (I + A dt/4))),
  // on the blocks of A = [A_aa, A_au; 0, D] when it has them (the arm states
  // a = b, phi_dot, b_dot; the rotor states u = omega, mu; D diagonal: the
  // motor lag and 0), as every power then has, and with A's kinematic rows
  // b_i_dot = b_dot_i (row b_i of A X is X's row b_dot_i): the same sums less
  // A's exact zeros. Else dense.
  // *blocks (when not null): whether it took the blocks (then Phi_d has them).
  static DynamicMatrix Transition(const DynamicMatrix& a, double dt_s, bool* blocks = nullptr);
  // Whether A_d (or Phi_d) is [X_aa, X_au; 0, D] with D diagonal and finite, exactly.
  static bool HasRotorBlockStructure(const DynamicMatrix& x);
  // Whether A_d's rows b_i are 0 but at b_dot_i, exactly (the kinematics b_i_dot = b_dot_i).
  static bool HasKinematicRows(const DynamicMatrix& x);
  // Phi_d X for a kD x C matrix X, on those blocks when blocks.
  static constexpr int kArmStates = 1 + 2 * N;  // b_i, phi_dot, b_dot_i
  static constexpr int kRotorStates = 2 * N;    // omega_i, mu_i
  template <int C, typename X>
  static Eigen::Matrix<double, kD, C> TransitionTimes(const DynamicMatrix& phi, const Eigen::MatrixBase<X>& x,
                                                      bool blocks) {
    constexpr int n = kArmStates, m = kRotorStates;
    Eigen::Matrix<double, kD, C> out;
    if (!blocks) {
      out.noalias() = phi.lazyProduct(x);
      return out;
    }
    auto top = out.template topRows<n>();
    top.noalias() = phi.template topLeftCorner<n, n>().lazyProduct(x.template topRows<n>());
    top.noalias() += phi.template topRightCorner<n, m>().lazyProduct(x.template bottomRows<m>());
    out.template bottomRows<m>() =
        phi.template bottomRightCorner<m, m>().diagonal().asDiagonal() * x.template bottomRows<m>();
    return out;
  }
  // Phi_d P Phi_d^T for a symmetric kD x kD P. On the blocks Phi_d = [F, G;
  // 0, D] (F arm, G arm-to-rotor, D diagonal) with X = F P_aa + G P_ua and
  // Y = F P_au + G P_uu (the rows of Phi_d P that are not diagonal scalings):
  //   P_aa+ = X F^T + Y G^T,  P_au+ = Y D,  P_uu+ = D P_uu D
  // (P_aa+ and P_uu+ on their upper triangles, mirrored: the result is
  // exactly symmetric, so the filter need not symmetrise P after it);
  // the same sums as (Phi_d (Phi_d P)^T)^T less the rotor rows' products.
  template <typename P>
  static DynamicMatrix Propagate(const DynamicMatrix& phi, const Eigen::MatrixBase<P>& p, bool blocks) {
    constexpr int n = kArmStates, m = kRotorStates;
    DynamicMatrix out;
    if (!blocks) {
      const DynamicMatrix temp = TransitionTimes<kD>(phi, p, false);
      out.noalias() = temp.lazyProduct(phi.transpose());
      return out;
    }
    const auto f = phi.template topLeftCorner<n, n>();
    const auto g = phi.template topRightCorner<n, m>();
    const Eigen::Matrix<double, m, 1> d = phi.template bottomRightCorner<m, m>().diagonal();
    Eigen::Matrix<double, n, n> x;
    x.noalias() = f.lazyProduct(p.template topLeftCorner<n, n>());
    x.noalias() += g.lazyProduct(p.template bottomLeftCorner<m, n>());
    Eigen::Matrix<double, n, m> y;
    y.noalias() = f.lazyProduct(p.template topRightCorner<n, m>());
    y.noalias() += g.lazyProduct(p.template bottomRightCorner<m, m>());
    for (int c = 0; c < n; ++c) {
      for (int r = 0; r <= c; ++r) {
        out(r, c) = out(c, r) = x.row(r).dot(f.row(c)) + y.row(r).dot(g.row(c));
      }
    }
    out.template topRightCorner<n, m>() = y * d.asDiagonal();
    out.template bottomLeftCorner<m, n>() = out.template topRightCorner<n, m>().transpose();
    out.template bottomRightCorner<m, m>() = d.asDiagonal() * p.template bottomRightCorner<m, m>() * d.asDiagonal();
    for (int c = 1; c < m; ++c) {  // D P_uu D's upper triangle mirrored
      for (int r = 0; r < c; ++r) out(n + c, n + r) = out(n + r, n + c);
    }
    return out;
  }

 private:
  double ThrustCoeff(int arm) const { return vehicle_.arms[static_cast<size_t>(arm)].thrust_coeff_n_s2_rad2; }
  double MotorTimeConstant(int arm) const { return vehicle_.arms[static_cast<size_t>(arm)].motor_time_constant_s; }
  static constexpr int kCoordinates = kBodyCoordinates + N;  // x, z, phi, b_i
  using Coordinates = Eigen::Matrix<double, kCoordinates, 1>;
  // q_ddot of the free body at phi = 0, at rest, from the arm states and
  // thrusts: MultiArmAcceleration's terms, solved by MassMatrixLdlt.
  Coordinates FreeAcceleration(double phi_dot, const std::array<double, N>& b, const std::array<double, N>& b_dot,
                               const std::array<double, N>& force_n) const;
  // x_dot from the free body's q_ddot at x (Derivative's rows).
  State DerivativeFrom(const State& x, const Input& u, const Coordinates& acc) const;
  // The held body (multi_arm_ekf_supported.h): arm i's b_ddot [rad/s^2], q_ddot
  // (x, z, phi rows 0) and A_d with f(x, u) into x_dot when non-null.
  template <typename T>
  T SupportedArmAcceleration(int arm, const T& b, const T& b_dot, const T& force_n) const;
  Coordinates SupportedAcceleration(const State& x) const;
  DynamicMatrix SupportedJacobian(const State& x, const Input& u, State* x_dot) const;

  VehicleDescription vehicle_;        // as flown (a learned tip mass)
  VehicleDescription file_vehicle_;   // as described
  LevelArmDirections<N> directions_;  // r_i, n_i at phi = 0
};

// One measurement model per sensor: h(x), H and R. A masked entry (an arm
// without a gauge, a NaN reading) is simply not measured: its row of H is
// zero, z = h = 0 there and its R entry 1 (any positive value): it adds
// nothing to the NIS, its gain column is zero, and S stays invertible.
template <int N>
struct MultiArmMeasurements {
  using Layout = MultiArmEkfLayout<N>;
  static constexpr int kS = Layout::kStateSize;
  using State = Eigen::Matrix<double, kS, 1>;
  using ArmVector = Eigen::Matrix<double, N, 1>;
  using ArmMatrix = Eigen::Matrix<double, N, N>;

  // Strain after calibration: z_i = b_i + e_i [rad] where measured[i].
  static MeasurementLinearization<N, kS> Strain(const State& x, const std::array<bool, N>& measured) {
    MeasurementLinearization<N, kS> at;
    at.jacobian.setZero();
    for (int i = 0; i < N; ++i) {
      at.predicted(i) = measured[i] ? x(Layout::Deflection(i)) + x(Layout::GaugeOffset(i)) : 0.0;
      if (!measured[i]) continue;
      at.jacobian(i, Layout::Deflection(i)) = 1.0;
      at.jacobian(i, Layout::GaugeOffset(i)) = 1.0;
    }
    return at;
  }
  // Motor telemetry: z_i = omega_i [rad/s] where measured[i].
  static MeasurementLinearization<N, kS> Telemetry(const State& x, const std::array<bool, N>& measured) {
    MeasurementLinearization<N, kS> at;
    at.jacobian.setZero();
    for (int i = 0; i < N; ++i) {
      at.predicted(i) = measured[i] ? x(Layout::Omega(i)) : 0.0;
      if (measured[i]) at.jacobian(i, Layout::Omega(i)) = 1.0;
    }
    return at;
  }
  // Gyro: z = phi_dot [rad/s].
  static MeasurementLinearization<1, kS> Gyro(const State& x) {
    MeasurementLinearization<1, kS> at;
    at.jacobian.setZero();
    at.jacobian(0, Layout::kPitchRate) = 1.0;
    at.predicted(0) = x(Layout::kPitchRate);
    return at;
  }
  // Accelerometer (a_x, a_z) [m/s^2] from the process Jacobian's by-product,
  // first order in the <= 1 ms the state moved since: h = a0 + H (x - x0).
  static MeasurementLinearization<2, kS> Accelerometer(const MultiArmAccelLinearization<N>& at0, const State& x) {
    MeasurementLinearization<2, kS> at;
    at.jacobian = at0.jacobian;
    at.predicted = at0.value + at0.jacobian * (x - at0.x0);
    return at;
  }
  // R = diag(sigma^2) on the measured entries, 1 on the masked ones.
  static ArmMatrix MaskedNoise(double noise_std, const std::array<bool, N>& measured) {
    ArmMatrix r = ArmMatrix::Zero();
    for (int i = 0; i < N; ++i) r(i, i) = measured[i] ? noise_std * noise_std : 1.0;
    return r;
  }
};

// ---- inline implementation ----

template <int N>
typename MultiArmEkfModel<N>::Coordinates MultiArmEkfModel<N>::FreeAcceleration(
    double phi_dot, const std::array<double, N>& b, const std::array<double, N>& b_dot,
    const std::array<double, N>& force_n) const {
  // q_ddot = M^-1 (tau - C - G), as MultiArmAcceleration at phi = 0, x = z = 0,
  // body velocity 0: the same terms, each arm's directions by LevelArmDirections.
  constexpr int n = kCoordinates;
  const MultiArmTerms<double> terms = AssembleMultiArmTerms<double>(vehicle_, [&](int i, MultiArmTerms<double>* out) {
    const size_t k = static_cast<size_t>(i);
    const ArmShare<double> share =
        MultiArmShareWith<double>(vehicle_, i, phi_dot + b_dot[k], b[k], b_dot[k], force_n[k], directions_.At(i, b[k]));
    AddArmTerms(share, DeflectionIndex(i), &out->mass, &out->coriolis, &out->gravity_spring, &out->generalized_thrust);
  });
  Coordinates acc = terms.generalized_thrust - terms.coriolis - terms.gravity_spring;
  MassMatrixLdlt<n>(Eigen::Matrix<double, n, n>(terms.mass)).SolveInPlace(&acc);
  return acc;
}

template <int N>
typename MultiArmEkfModel<N>::State MultiArmEkfModel<N>::Derivative(const State& x, const Input& u) const {
  if (u.supported) return DerivativeFrom(x, u, SupportedAcceleration(x));
  std::array<double, N> b, b_dot, f;
  for (int i = 0; i < N; ++i) {
    b[i] = x(Layout::Deflection(i));
    b_dot[i] = x(Layout::DeflectionRate(i));
    f[i] = Force(x, i);
  }
  return DerivativeFrom(x, u, FreeAcceleration(x(Layout::kPitchRate), b, b_dot, f));
}

template <int N>
typename MultiArmEkfModel<N>::State MultiArmEkfModel<N>::DerivativeFrom(const State& x, const Input& u,
                                                                        const Coordinates& acc) const {
  State x_dot = State::Zero();  // mu and e: random walks
  x_dot(Layout::kPitchRate) = acc(kPhi);
  for (int i = 0; i < N; ++i) {
    x_dot(Layout::Deflection(i)) = x(Layout::DeflectionRate(i));
    x_dot(Layout::DeflectionRate(i)) = acc(DeflectionIndex(i));
    x_dot(Layout::Omega(i)) = (ClampCommand(u.omega_cmd_rad_s[i]) - x(Layout::Omega(i))) / MotorTimeConstant(i);
  }
  return x_dot;
}

template <int N>
typename MultiArmEkfModel<N>::DynamicMatrix MultiArmEkfModel<N>::Jacobian(const State& x, const Input& u,
                                                                          MultiArmAccelLinearization<N>* accel,
                                                                          State* x_dot) const {
  if (u.supported) return SupportedJacobian(x, u, x_dot);  // no accelerometer linearisation on the ground
  // Jets through the terms M, C, G, tau of the Euler-Lagrange equations only;
  // the solve differentiated by hand on doubles, as EkfProcessModel::Jacobian:
  //   q_ddot = M^-1 r,  d q_ddot = M^-1 (dr - dM q_ddot),  r = tau - C - G
  // (a third of the cost of Jets through the solve).
  // Each arm's share on Jets over its own 4 variables (b_i, phi_dot, b_dot_i,
  // f_i) at phi = 0, scattered into the 1 + 3N wide ones (multi_arm_ekf_jets.h).
  constexpr int n = kBodyCoordinates + N, k = Layout::kJetSize;
  using Jet = ceres::Jet<double, k>;
  const MultiArmTerms<Jet> terms = AssembleMultiArmTerms<Jet>(vehicle_, [&](int i, MultiArmTerms<Jet>* out) {
    const ArmJet phi_dot(x(Layout::kPitchRate), kArmJetPitchRate);
    const ArmJet b(x(Layout::Deflection(i)), kArmJetDeflection);
    const ArmJet b_dot(x(Layout::DeflectionRate(i)), kArmJetDeflectionRate);
    const ArmJet force(Force(x, i), kArmJetForce);
    const std::array<int, kArmJetSize> columns = {Layout::Dynamic(Layout::Deflection(i)),
                                                  Layout::Dynamic(Layout::kPitchRate),
                                                  Layout::Dynamic(Layout::DeflectionRate(i)), Layout::JetForce(i)};
    const ArmShare<ArmJet> share =
        MultiArmShareWith<ArmJet>(vehicle_, i, phi_dot + b_dot, b, b_dot, force, directions_.At(i, b));
    AddScatteredArmTerms<k>(share, DeflectionIndex(i), columns, out);
  });
  Eigen::Matrix<double, n, n> mass;
  Eigen::Matrix<double, n, 1> rhs;
  // Row-major: the solve works row by row over the k derivative columns.
  Eigen::Matrix<double, n, k, Eigen::RowMajor> d_rhs;
  for (int i = 0; i < n; ++i) {
    const Jet r = terms.generalized_thrust(i) - terms.coriolis(i) - terms.gravity_spring(i);
    rhs(i) = r.a;
    d_rhs.row(i) = r.v.transpose();
    for (int j = 0; j < n; ++j) mass(i, j) = terms.mass(i, j).a;
  }
  const MassMatrixLdlt<n> ldlt(mass);  // doubles: no Jet-equality pitfall
  Coordinates acc_value = rhs;
  ldlt.SolveInPlace(&acc_value);
  if (x_dot != nullptr) *x_dot = DerivativeFrom(x, u, acc_value);
  // M = M(q) depends on the configuration alone: at phi = 0 on the b_i, the
  // Jet's first N variables; its derivatives in the others are exact zeros
  // (x - 0 y = x), left out.
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      d_rhs.row(i).template head<N>() -= terms.mass(i, j).v.template head<N>().transpose() * acc_value(j);
    }
  }
  Eigen::Matrix<double, n, k, Eigen::RowMajor> d_acc = d_rhs;
  ldlt.SolveInPlace(&d_acc);
  MultiCoords<Jet> acc(n);
  for (int i = 0; i < n; ++i) acc(i) = Jet(acc_value(i), d_acc.row(i).transpose());
  std::array<Eigen::Vector2d, N> grad;  // (df/domega, df/dmu)
  for (int i = 0; i < N; ++i) grad[i] = ForceGradient(x, i);
  // One row of d(acceleration)/dx over the dynamic states from a Jet: the
  // first 1 + 2N are the Jet's own variables, omega_i and mu_i by the chain
  // rule through f_i.
  const auto fill_row = [&](const Jet& a, auto&& row) {
    for (int c = 0; c < 1 + 2 * N; ++c) row(c) = a.v(c);
    for (int i = 0; i < N; ++i) {
      row(Layout::Dynamic(Layout::Omega(i))) = a.v(Layout::JetForce(i)) * grad[i](0);
      row(Layout::Dynamic(Layout::ThrustScale(i))) = a.v(Layout::JetForce(i)) * grad[i](1);
    }
  };
  const auto d = [](int state) { return Layout::Dynamic(state); };
  DynamicMatrix a = DynamicMatrix::Zero();
  fill_row(acc(kPhi), a.row(d(Layout::kPitchRate)));
  for (int i = 0; i < N; ++i) {
    a(d(Layout::Deflection(i)), d(Layout::DeflectionRate(i))) = 1.0;
    fill_row(acc(DeflectionIndex(i)), a.row(d(Layout::DeflectionRate(i))));
    a(d(Layout::Omega(i)), d(Layout::Omega(i))) = -1.0 / MotorTimeConstant(i);
  }
  if (accel != nullptr) {
    constexpr int first = Layout::kFirstDynamic;
    accel->x0 = x;
    accel->value = Eigen::Vector2d(acc(kX).a, acc(kZ).a + vehicle_.gravity_m_s2);
    accel->jacobian.setZero();
    fill_row(acc(kX), accel->jacobian.row(0).template segment<kD>(first));
    fill_row(acc(kZ), accel->jacobian.row(1).template segment<kD>(first));
  }
  return a;
}

extern template class MultiArmEkfModel<2>;
extern template class MultiArmEkfModel<3>;
extern template class MultiArmEkfModel<4>;
extern template class MultiArmEkfModel<5>;
extern template class MultiArmEkfModel<6>;

}  // namespace birotor
