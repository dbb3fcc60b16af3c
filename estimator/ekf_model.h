// State, process model and measurement models of the rotor-force EKF.
// The state holds what the strain gauges observe (thesis ch. 4): the arm
// deflections and rates, the body pitch rate, the rotor speeds and the thrust
// scales mu_i, so that f_i = mu_i c_T omega_i^2; and the zero offset e_i that
// each calibrated gauge still has (shared/spec/gauges.md: power-up offset
// left by the tare, thermal drift), so that a gauge reads b_i + e_i.
#pragma once

#include <ceres/jet.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>

#include "estimator/kalman_fusion.h"
#include "model/arm_dynamics.h"
#include "model/birotor_dynamics.h"
#include "model/plant.h"
#include "model/rk4.h"
#include "model/vehicle_params.h"

namespace birotor {

// Named indices of the filter state.
enum EkfIndex : int {
  kDeflection1 = 0,      // b1 [rad]
  kDeflection2 = 1,      // b2 [rad]
  kPitchRate = 2,        // phi_dot [rad/s]
  kDeflectionRate1 = 3,  // b1_dot [rad/s]
  kDeflectionRate2 = 4,  // b2_dot [rad/s]
  kOmega1 = 5,           // rotor 1 speed [rad/s]
  kOmega2 = 6,           // rotor 2 speed [rad/s]
  kThrustScale1 = 7,     // mu1 [1]
  kThrustScale2 = 8,     // mu2 [1]
  kGaugeOffset1 = 9,     // e1: offset of calibrated gauge 1, in deflection [rad]
  kGaugeOffset2 = 10,    // e2 [rad]
};
constexpr int kEkfStateSize = 11;
// The states with dynamics come first; the offsets are random walks
// (e_dot = 0), so the transition matrix is blockdiag(Phi_d, I) and the
// prediction works on the dynamic block (the model's structure pays for the
// two extra states).
constexpr int kDynamicStateSize = 9;
constexpr EkfIndex kDeflectionIndex[2] = {kDeflection1, kDeflection2};
constexpr EkfIndex kDeflectionRateIndex[2] = {kDeflectionRate1, kDeflectionRate2};
constexpr EkfIndex kOmegaIndex[2] = {kOmega1, kOmega2};
constexpr EkfIndex kThrustScaleIndex[2] = {kThrustScale1, kThrustScale2};
constexpr EkfIndex kGaugeOffsetIndex[2] = {kGaugeOffset1, kGaugeOffset2};

using EkfState = Eigen::Matrix<double, kEkfStateSize, 1>;
using EkfMatrix = Eigen::Matrix<double, kEkfStateSize, kEkfStateSize>;
using DynamicMatrix = Eigen::Matrix<double, kDynamicStateSize, kDynamicStateSize>;

// Input held over one prediction interval: clamped rotor speed commands, and
// whether a support (the ground) holds the body (GroundContact decides).
struct EkfInput {
  double omega_cmd_rad_s[2] = {0, 0};
  bool body_supported = false;
};

// The accelerometer's model linearised where the process was (free body):
// a_z(x) ~ a_z0 + H (x - x0), a by-product of the process Jacobian (the z row
// of the same solve), so the IMU fusion costs no second evaluation.
struct AccelerometerLinearization {
  bool valid = false;  // false after a supported-body step (no free-body solve)
  EkfState x0 = EkfState::Zero();
  double a_z0_m_s2 = 0;                                                                         // a_z(x0)
  Eigen::Matrix<double, 1, kEkfStateSize> h = Eigen::Matrix<double, 1, kEkfStateSize>::Zero();  // d a_z / dx
};

// Process model x_dot = f(x, u):
//   [phi_ddot, b_dot, b_ddot] from FreeArmDerivative (model/arm_dynamics.h: the
//   phi, b1, b2 rows of thesis eq. 3.14, which for a free body in uniform
//   gravity do not depend on x, z, phi, x_dot, z_dot) with f_i = mu_i c_T omega_i^2,
//   omega_i_dot = (clamp(omega_cmd_i) - omega_i) / tau_m,
//   mu_i_dot = 0 and e_i_dot = 0 (random walks, driven by process noise).
// On the ground (u.body_supported) the body is held still: phi_ddot = 0 and
// b_ddot from SupportedArmAcceleration, where the arms also carry their weight.
class EkfProcessModel {
 public:
  explicit EkfProcessModel(const VehicleParams& params) : params_(params) {}

  EkfState Derivative(const EkfState& x, const EkfInput& u) const;
  // A_d = df/dx on the dynamic block (the offset rows and columns of A are
  // zero): Jets over (b1, b2, phi_dot, b1_dot, b2_dot, f1, f2) and the chain
  // rule df/domega = 2 mu c_T omega, df/dmu = c_T omega^2.
  // With accel non-null it also gets a_z and its gradient at x (free body;
  // marked invalid on the ground).
  DynamicMatrix Jacobian(const EkfState& x, const EkfInput& u, AccelerometerLinearization* accel = nullptr) const;
  // A_d for a body held by the ground: Jets through SupportedArmAcceleration
  // over (b1, b2, b1_dot, b2_dot, f1, f2); the phi_dot row is zero.
  DynamicMatrix SupportedJacobian(const EkfState& x) const;
  // One RK4 step over dt_s with u held.
  EkfState Step(const EkfState& x, const EkfInput& u, double dt_s) const;
  // Transition matrix of the dynamic block, Phi_d = exp(A_d dt) to fourth order:
  //   I + A dt + (A dt)^2/2 + (A dt)^3/6 + (A dt)^4/24
  // (arm modes ~500 rad/s, dt = 1 ms: |A dt| ~ 0.5, truncation ~ 3e-4).
  static DynamicMatrix Transition(const DynamicMatrix& a, double dt_s);

  // f_i = mu_i c_T omega_i^2 [N].
  double Force(const EkfState& x, int rotor) const {
    const double omega = x(kOmegaIndex[rotor]);
    return x(kThrustScaleIndex[rotor]) * params_.thrust_coeff_n_s2_rad2 * omega * omega;
  }
  // Gradient of f_i with respect to (omega_i, mu_i).
  Eigen::Vector2d ForceGradient(const EkfState& x, int rotor) const {
    const double omega = x(kOmegaIndex[rotor]);
    const double c_t = params_.thrust_coeff_n_s2_rad2;
    return Eigen::Vector2d(2.0 * x(kThrustScaleIndex[rotor]) * c_t * omega, c_t * omega * omega);
  }
  const VehicleParams& params() const { return params_; }

 private:
  VehicleParams params_;
};

// One measurement model per sensor: z = h(x) + noise, noise ~ N(0, R).
// Each returns h(x) and H at the prior (Linearize, const: a model never
// changes itself); estimator/kalman_fusion.h fuses them. H is constant for
// strain, telemetry and gyro (they read states directly); the
// accelerometer's is evaluated at the state.

// What every model has: its size M and R = sigma^2 I (independent readings
// of one noise sigma, in the measurement's unit).
template <int M>
struct MeasurementModel {
  static constexpr int kSize = M;
  using Vector = Eigen::Matrix<double, M, 1>;
  using Jacobian = Eigen::Matrix<double, M, kEkfStateSize>;
  using Covariance = Eigen::Matrix<double, M, M>;
  using Linearization = MeasurementLinearization<M, kEkfStateSize>;
  explicit MeasurementModel(double noise_std) : noise(Covariance::Identity() * (noise_std * noise_std)) {}
  const Covariance noise;  // R [unit of z squared]
};

// A model that reads states directly: H constant, set once by the model.
template <int M>
struct LinearMeasurementModel : MeasurementModel<M> {
  using typename MeasurementModel<M>::Jacobian;
  using typename MeasurementModel<M>::Linearization;
  LinearMeasurementModel(double noise_std, const Jacobian& h) : MeasurementModel<M>(noise_std), h_jacobian(h) {}
  // h(x) = H x.
  Linearization Linearize(const EkfState& x) const {
    Linearization at;
    at.predicted.noalias() = h_jacobian.lazyProduct(x);
    at.jacobian = h_jacobian;
    return at;
  }
  const Jacobian h_jacobian;  // H [unit of z per unit of each state]
};

// H of a model reading the sum of the listed states, one row per reading.
template <int M>
Eigen::Matrix<double, M, kEkfStateSize> SelectionJacobian(const EkfIndex (&first)[M],
                                                          const EkfIndex (*second)[M] = nullptr) {
  Eigen::Matrix<double, M, kEkfStateSize> h = Eigen::Matrix<double, M, kEkfStateSize>::Zero();
  for (int i = 0; i < M; ++i) {
    h(i, first[i]) = 1.0;
    if (second != nullptr) h(i, (*second)[i]) = 1.0;
  }
  return h;
}

// Strain gauges after calibration: z_i = b_i + e_i [rad], noise_std in rad.
struct StrainMeasurementModel : LinearMeasurementModel<2> {
  explicit StrainMeasurementModel(double noise_std)
      : LinearMeasurementModel<2>(noise_std, SelectionJacobian<2>(kDeflectionIndex, &kGaugeOffsetIndex)) {}
};
// Motor telemetry: z = (omega1, omega2) [rad/s], noise_std in rad/s.
struct MotorSpeedMeasurementModel : LinearMeasurementModel<2> {
  explicit MotorSpeedMeasurementModel(double noise_std)
      : LinearMeasurementModel<2>(noise_std, SelectionJacobian<2>(kOmegaIndex)) {}
};

// Gyro: z = phi_dot (body pitch rate; the body rate of a rigid body is the
// same in every frame of the plane).
struct GyroMeasurementModel : LinearMeasurementModel<1> {
  explicit GyroMeasurementModel(double noise_rad_s)
      : LinearMeasurementModel<1>(noise_rad_s, SelectionJacobian<1>({kPitchRate})) {}
};

// Accelerometer: z = a_z, the specific force along the body z axis at the
// body centre [m/s^2] in free flight (FreeArmDerivative's specific force:
// (f1 + f2) / (m + 2 m_p) at rest, plus the arms' reaction while they swing).
// It weighs the total thrust independently of the gauges, which is what
// separates e1 - e2 from f1 + f2: the strain alone sees b1 - b2, which both
// move (thesis eq. 3.34). h and H are evaluated at the state (Linearize);
// not used while the ground holds the body (then a_z is the support).
struct AccelerometerMeasurementModel : MeasurementModel<1> {
  explicit AccelerometerMeasurementModel(double noise_m_s2) : MeasurementModel<1>(noise_m_s2) {}
  // h(x) and H at x (Jets over b1, b2, phi_dot, b1_dot, b2_dot, f1, f2; chain
  // rule to omega_i, mu_i as in the process Jacobian).
  static Linearization Linearize(const EkfProcessModel& process, const EkfState& x);
  // The same from the process Jacobian's by-product at x0 (valid): H = the
  // gradient there and h(x) = a_z0 + H (x - x0), first order in the <= 1 ms
  // the state moved since (the filter's usual linearisation at the prior).
  static Linearization Linearize(const AccelerometerLinearization& at, const EkfState& x) {
    Linearization out;
    out.jacobian = at.h;
    out.predicted(0) = at.a_z0_m_s2 + at.h.dot(x - at.x0);
    return out;
  }
};

// ---- inline implementation of EkfProcessModel ----

inline EkfState EkfProcessModel::Derivative(const EkfState& x, const EkfInput& u) const {
  FreeArmState<double> arm;
  arm(kFreePhiDot) = x(kPitchRate);
  arm(kFreeB1) = x(kDeflection1);
  arm(kFreeB2) = x(kDeflection2);
  arm(kFreeB1Dot) = x(kDeflectionRate1);
  arm(kFreeB2Dot) = x(kDeflectionRate2);
  const FreeArmState<double> arm_dot = FreeArmDerivative<double>(
      params_, params_.arm_stiffness_n_m_rad, params_.arm_damping_n_m_s_rad, arm, Force(x, 0), Force(x, 1));
  EkfState x_dot;
  x_dot(kDeflection1) = arm_dot(kFreeB1);
  x_dot(kDeflection2) = arm_dot(kFreeB2);
  x_dot(kPitchRate) = arm_dot(kFreePhiDot);
  x_dot(kDeflectionRate1) = arm_dot(kFreeB1Dot);
  x_dot(kDeflectionRate2) = arm_dot(kFreeB2Dot);
  x_dot(kGaugeOffset1) = 0.0;
  x_dot(kGaugeOffset2) = 0.0;
  if (u.body_supported) {
    const Eigen::Vector2d b_ddot = SupportedArmAcceleration<double>(
        params_, x(kDeflection1), x(kDeflection2), x(kDeflectionRate1), x(kDeflectionRate2), Force(x, 0), Force(x, 1));
    x_dot(kPitchRate) = 0.0;
    x_dot(kDeflectionRate1) = b_ddot(0);
    x_dot(kDeflectionRate2) = b_ddot(1);
  }
  for (int i = 0; i < 2; ++i) {
    x_dot(kOmegaIndex[i]) =
        (ClampCommand(params_, u.omega_cmd_rad_s[i]) - x(kOmegaIndex[i])) / params_.motor_time_constant_s;
    x_dot(kThrustScaleIndex[i]) = 0.0;
  }
  return x_dot;
}

inline DynamicMatrix EkfProcessModel::Jacobian(const EkfState& x, const EkfInput& u,
                                               AccelerometerLinearization* accel) const {
  if (u.body_supported) {
    if (accel != nullptr) accel->valid = false;
    return SupportedJacobian(x);
  }
  // Jet variables: 0..4 = b1, b2, phi_dot, b1_dot, b2_dot; 5, 6 = f1, f2; the
  // eighth is padding so that the derivative part vectorises (4 SSE packets).
  // The terms of thesis eq. 3.10 are differentiated with Jets; the solve is
  // differentiated by hand, d(M^-1 r) = M^-1 (dr - dM M^-1 r), so that the
  // Cholesky factorisation runs on doubles (the same Jacobian as Jets through
  // GeneralizedAcceleration, at a third of the cost).
  constexpr int kJetSize = 8;
  using Jet = ceres::Jet<double, kJetSize>;
  Coords<Jet> q, v;
  q << Jet(0.0), Jet(0.0), Jet(0.0), Jet(x(kDeflection1), 0), Jet(x(kDeflection2), 1);
  v << Jet(0.0), Jet(0.0), Jet(x(kPitchRate), 2), Jet(x(kDeflectionRate1), 3), Jet(x(kDeflectionRate2), 4);
  const DynamicsTerms<Jet> terms = ComputeDynamicsTerms<Jet>(params_, q, v, Jet(Force(x, 0), 5), Jet(Force(x, 1), 6));
  CoordMatrix<double> mass;
  Coords<double> rhs;
  Eigen::Matrix<double, kNumCoordinates, kJetSize> d_rhs;
  for (int i = 0; i < kNumCoordinates; ++i) {
    const Jet r = terms.generalized_thrust(i) - terms.coriolis(i) - terms.gravity_spring(i);
    rhs(i) = r.a;
    d_rhs.row(i) = r.v.transpose();
    for (int j = 0; j < kNumCoordinates; ++j) mass(i, j) = terms.mass(i, j).a;
  }
  const Eigen::LLT<CoordMatrix<double>> llt(mass);
  const Coords<double> acc_full = llt.solve(rhs);
  for (int i = 0; i < kNumCoordinates; ++i) {
    for (int j = 0; j < kNumCoordinates; ++j) d_rhs.row(i) -= terms.mass(i, j).v.transpose() * acc_full(j);
  }
  const Eigen::Matrix<double, kNumCoordinates, kJetSize> d_acc = llt.solve(d_rhs);

  constexpr EkfIndex kJetState[5] = {kDeflection1, kDeflection2, kPitchRate, kDeflectionRate1, kDeflectionRate2};
  constexpr EkfIndex kAccRow[3] = {kPitchRate, kDeflectionRate1, kDeflectionRate2};
  constexpr Coordinate kAccCoordinate[3] = {kPhi, kB1, kB2};
  DynamicMatrix a = DynamicMatrix::Zero();
  a(kDeflection1, kDeflectionRate1) = 1.0;
  a(kDeflection2, kDeflectionRate2) = 1.0;
  const Eigen::Vector2d grad[2] = {ForceGradient(x, 0), ForceGradient(x, 1)};  // (df/domega, df/dmu)
  for (int r = 0; r < 3; ++r) {
    const int row = kAccCoordinate[r];
    for (int c = 0; c < 5; ++c) a(kAccRow[r], kJetState[c]) = d_acc(row, c);
    for (int i = 0; i < 2; ++i) {
      a(kAccRow[r], kOmegaIndex[i]) = d_acc(row, 5 + i) * grad[i](0);
      a(kAccRow[r], kThrustScaleIndex[i]) = d_acc(row, 5 + i) * grad[i](1);
    }
  }
  a(kOmega1, kOmega1) = -1.0 / params_.motor_time_constant_s;
  a(kOmega2, kOmega2) = -1.0 / params_.motor_time_constant_s;
  if (accel != nullptr) {
    // Specific force along body z at phi = 0: z_ddot + g (gravity is in the solve).
    accel->valid = true;
    accel->x0 = x;
    accel->a_z0_m_s2 = acc_full(kZ) + params_.gravity_m_s2;
    accel->h.setZero();
    for (int c = 0; c < 5; ++c) accel->h(kJetState[c]) = d_acc(kZ, c);
    for (int i = 0; i < 2; ++i) {
      accel->h(kOmegaIndex[i]) = d_acc(kZ, 5 + i) * grad[i](0);
      accel->h(kThrustScaleIndex[i]) = d_acc(kZ, 5 + i) * grad[i](1);
    }
  }
  return a;
}

inline DynamicMatrix EkfProcessModel::SupportedJacobian(const EkfState& x) const {
  using Jet = ceres::Jet<double, 6>;
  const Eigen::Matrix<Jet, 2, 1> acc = SupportedArmAcceleration<Jet>(
      params_, Jet(x(kDeflection1), 0), Jet(x(kDeflection2), 1), Jet(x(kDeflectionRate1), 2),
      Jet(x(kDeflectionRate2), 3), Jet(Force(x, 0), 4), Jet(Force(x, 1), 5));
  constexpr EkfIndex kJetState[4] = {kDeflection1, kDeflection2, kDeflectionRate1, kDeflectionRate2};
  DynamicMatrix a = DynamicMatrix::Zero();
  a(kDeflection1, kDeflectionRate1) = 1.0;
  a(kDeflection2, kDeflectionRate2) = 1.0;
  const Eigen::Vector2d grad[2] = {ForceGradient(x, 0), ForceGradient(x, 1)};  // (df/domega, df/dmu)
  for (int r = 0; r < 2; ++r) {
    const int row = kDeflectionRateIndex[r];
    for (int c = 0; c < 4; ++c) a(row, kJetState[c]) = acc(r).v(c);
    for (int i = 0; i < 2; ++i) {
      a(row, kOmegaIndex[i]) = acc(r).v(4 + i) * grad[i](0);
      a(row, kThrustScaleIndex[i]) = acc(r).v(4 + i) * grad[i](1);
    }
  }
  a(kOmega1, kOmega1) = -1.0 / params_.motor_time_constant_s;
  a(kOmega2, kOmega2) = -1.0 / params_.motor_time_constant_s;
  return a;
}

inline EkfState EkfProcessModel::Step(const EkfState& x, const EkfInput& u, double dt_s) const {
  return Rk4Step(x, dt_s, [&](const EkfState& s) { return Derivative(s, u); });
}

inline DynamicMatrix EkfProcessModel::Transition(const DynamicMatrix& a, double dt_s) {
  // Horner form: I + A dt (I + A dt/2 (I + A dt/3 (I + A dt/4))).
  // lazyProduct: coefficient-based products, faster than GEMM at 9x9.
  const DynamicMatrix a_dt = a * dt_s;
  DynamicMatrix phi = DynamicMatrix::Identity() + a_dt * 0.25;
  DynamicMatrix temp;
  temp.noalias() = a_dt.lazyProduct(phi);
  phi = DynamicMatrix::Identity() + temp * (1.0 / 3.0);
  temp.noalias() = a_dt.lazyProduct(phi);
  phi = DynamicMatrix::Identity() + temp * 0.5;
  temp.noalias() = a_dt.lazyProduct(phi);
  return DynamicMatrix::Identity() + temp;
}

inline AccelerometerMeasurementModel::Linearization AccelerometerMeasurementModel::Linearize(
    const EkfProcessModel& process, const EkfState& x) {
  constexpr int kJetSize = 8;  // 7 variables and one of padding (vectorises)
  using Jet = ceres::Jet<double, kJetSize>;
  const VehicleParams& params = process.params();
  FreeArmState<Jet> arm;
  arm(kFreeB1) = Jet(x(kDeflection1), 0);
  arm(kFreeB2) = Jet(x(kDeflection2), 1);
  arm(kFreePhiDot) = Jet(x(kPitchRate), 2);
  arm(kFreeB1Dot) = Jet(x(kDeflectionRate1), 3);
  arm(kFreeB2Dot) = Jet(x(kDeflectionRate2), 4);
  Eigen::Matrix<Jet, 2, 1> specific_force;
  FreeArmDerivative<Jet>(params, Jet(params.arm_stiffness_n_m_rad), Jet(params.arm_damping_n_m_s_rad), arm,
                         Jet(process.Force(x, 0), 5), Jet(process.Force(x, 1), 6), &specific_force);
  const Jet& a_z = specific_force(1);
  Linearization out;
  out.jacobian.setZero();
  out.jacobian(0, kDeflection1) = a_z.v(0);
  out.jacobian(0, kDeflection2) = a_z.v(1);
  out.jacobian(0, kPitchRate) = a_z.v(2);
  out.jacobian(0, kDeflectionRate1) = a_z.v(3);
  out.jacobian(0, kDeflectionRate2) = a_z.v(4);
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector2d grad = process.ForceGradient(x, i);  // (df/domega, df/dmu)
    out.jacobian(0, kOmegaIndex[i]) = a_z.v(5 + i) * grad(0);
    out.jacobian(0, kThrustScaleIndex[i]) = a_z.v(5 + i) * grad(1);
  }
  out.predicted(0) = a_z.a;
  return out;
}

}  // namespace birotor
