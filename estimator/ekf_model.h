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
#include "model/birotor_params.h"
#include "model/plant.h"
#include "model/rk4.h"
#include "samples/rotor_count.h"

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
  // Slow vehicle parameters learned in flight (issue 27, docs/mismatch.md):
  // random walks, exactly 1 with zero variance when not learned.
  kStrainScale1 = 11,   // g1: calibrated gauge 1 reads g1 b1 + e1 [1] (s_true k_file / (s_file k_true))
  kStrainScale2 = 12,   // g2 [1]
  kBodyMassScale = 13,  // r_m: body mass m = r_m m_file [1] (a payload)
};
constexpr int kEkfStateSize = 14;
// The states with dynamics come first; the offsets and the slow parameters
// are random walks (x_dot = 0), so the transition matrix is
// [Phi_d, Gamma; 0, I] with Gamma non-zero only in the body-mass column (the
// mass enters the dynamics; the gauge offsets and scales only the strain
// reading), and the prediction works on the dynamic block.
constexpr int kDynamicStateSize = 9;
constexpr int kSlowStateSize = kEkfStateSize - kDynamicStateSize;
constexpr EkfIndex kDeflectionIndex[kBirotorRotors] = {kDeflection1, kDeflection2};
constexpr EkfIndex kDeflectionRateIndex[kBirotorRotors] = {kDeflectionRate1, kDeflectionRate2};
constexpr EkfIndex kOmegaIndex[kBirotorRotors] = {kOmega1, kOmega2};
constexpr EkfIndex kThrustScaleIndex[kBirotorRotors] = {kThrustScale1, kThrustScale2};
constexpr EkfIndex kGaugeOffsetIndex[kBirotorRotors] = {kGaugeOffset1, kGaugeOffset2};
constexpr EkfIndex kStrainScaleIndex[kBirotorRotors] = {kStrainScale1, kStrainScale2};
constexpr double kStrainScaleVarianceCeiling = 0.25;  // of var(g_i) in P and of its published sigma^2 [1]

using EkfState = Eigen::Matrix<double, kEkfStateSize, 1>;
using EkfMatrix = Eigen::Matrix<double, kEkfStateSize, kEkfStateSize>;
using DynamicMatrix = Eigen::Matrix<double, kDynamicStateSize, kDynamicStateSize>;
using DynamicVector = Eigen::Matrix<double, kDynamicStateSize, 1>;

// Input held over one prediction interval: clamped rotor speed commands, and
// whether a support (the ground) holds the body (GroundContact decides).
struct EkfInput {
  double omega_cmd_rad_s[kBirotorRotors] = {0, 0};
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
//   mu_i_dot = 0, e_i_dot = 0, g_i_dot = 0, r_m_dot = 0 (random walks, driven
//   by process noise); the body mass in the dynamics is r_m m_file.
// On the ground (u.body_supported) the body is held still: phi_ddot = 0 and
// b_ddot from SupportedArmAcceleration, where the arms also carry their weight.
class EkfProcessModel {
 public:
  // body_mass_is_state: the body mass is r_m m_file (kBodyMassScale) and the
  // Jacobian has its column; false: the file's mass, whatever r_m holds.
  explicit EkfProcessModel(const BirotorParams& params, bool body_mass_is_state = false)
      : params_(params), body_mass_is_state_(body_mass_is_state) {}

  EkfState Derivative(const EkfState& x, const EkfInput& u) const;
  // A_d = df/dx on the dynamic block (the offset rows and columns of A are
  // zero): Jets over (b1, b2, phi_dot, b1_dot, b2_dot, f1, f2) and the chain
  // rule df/domega = 2 mu c_T omega, df/dmu = c_T omega^2.
  // With accel non-null it also gets a_z and its gradient at x (free body;
  // marked invalid on the ground).
  // With mass_column non-null and the body mass a state, it also gets
  // d f_d / d r_m (zero on the ground, where the body mass is carried), by
  // central differences of FreeArmDerivative (the dynamics are smooth in
  // 1 / M; two double evaluations instead of a ninth Jet variable).
  DynamicMatrix Jacobian(const EkfState& x, const EkfInput& u, AccelerometerLinearization* accel = nullptr,
                         DynamicVector* mass_column = nullptr) const;
  // A_d for a body held by the ground: Jets through SupportedArmAcceleration
  // over (b1, b2, b1_dot, b2_dot, f1, f2); the phi_dot row is zero.
  DynamicMatrix SupportedJacobian(const EkfState& x) const;
  // One RK4 step over dt_s with u held.
  EkfState Step(const EkfState& x, const EkfInput& u, double dt_s) const;
  // Transition matrix of the dynamic block, Phi_d = exp(A_d dt) to fourth order:
  //   I + A dt + (A dt)^2/2 + (A dt)^3/6 + (A dt)^4/24
  // (arm modes ~500 rad/s, dt = 1 ms: |A dt| ~ 0.5, truncation ~ 3e-4).
  // (estimator/ekf_prediction.cc, with the check of A's block structure the
  // fast path relies on, HasRotorBlockStructure). With column and gamma
  // non-null it also gives ParameterTransition's Gamma for that column c,
  // from the Horner factor W = I + A dt/2 (I + A dt/3 (I + A dt/4)) of
  // Phi_d = I + A dt W: Gamma = W c dt (on W's blocks; the same polynomial).
  static DynamicMatrix Transition(const DynamicMatrix& a, double dt_s, const DynamicVector* column = nullptr,
                                  DynamicVector* gamma = nullptr);
  // Whether A_d (or Phi_d) is [X_aa, X_au; 0, D] with D diagonal, exactly.
  static bool HasRotorBlockStructure(const DynamicMatrix& x);
  // The transition's column of a constant parameter p entering as
  // x_d_dot = A x_d + c p: Gamma = int_0^dt exp(A s) ds c, to the same order
  //   dt (I + A dt/2 (I + A dt/3 (I + A dt/4))) c.
  static DynamicVector ParameterTransition(const DynamicMatrix& a, const DynamicVector& c, double dt_s);

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
  const BirotorParams& params() const { return params_; }
  // The tip mass the dynamics use from now on (learned from the arm mode) [kg].
  void SetTipMassKg(double tip_mass_kg) { params_.tip_mass_kg = tip_mass_kg; }
  bool body_mass_is_state() const { return body_mass_is_state_; }
  // The vehicle at x: the file's, with the body mass r_m m_file when it is a state.
  BirotorParams ParamsAt(const EkfState& x) const {
    BirotorParams p = params_;
    if (body_mass_is_state_) p.body_mass_kg *= x(kBodyMassScale);
    return p;
  }
  // d (arm rates, specific force z) / d r_m at x in free flight, central
  // differences: (phi_ddot, b1_ddot, b2_ddot) into column rows, d a_z / d r_m returned.
  double MassDerivative(const EkfState& x, DynamicVector* column) const;

 private:
  BirotorParams params_;
  bool body_mass_is_state_ = false;
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

// Strain gauges after calibration: z_i = g_i b_i + e_i [rad], noise_std in
// rad. g_i is 1 unless learned (kStrainScaleIndex): the true gauge scale over
// the file's times the file's stiffness over the true one, which the strain
// alone cannot tell apart (at steady state b_i is proportional to 1 / k_i).
// H: dz_i/db_i = g_i, dz_i/dg_i = b_i, dz_i/de_i = 1.
struct StrainMeasurementModel : MeasurementModel<2> {
  explicit StrainMeasurementModel(double noise_std) : MeasurementModel<2>(noise_std) {}
  static Linearization Linearize(const EkfState& x) {
    Linearization at;
    at.jacobian.setZero();
    for (int i = 0; i < kBirotorRotors; ++i) {
      const int b = kDeflectionIndex[i], e = kGaugeOffsetIndex[i], g = kStrainScaleIndex[i];
      at.predicted(i) = x(g) * x(b) + x(e);
      at.jacobian(i, b) = x(g);
      at.jacobian(i, g) = x(b);
      at.jacobian(i, e) = 1.0;
    }
    return at;
  }
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

// The (phi_dot, b1, b2, b1_dot, b2_dot) of FreeArmDerivative from the filter state.
inline FreeArmState<double> ArmState(const EkfState& x) {
  FreeArmState<double> arm;
  arm(kFreePhiDot) = x(kPitchRate);
  arm(kFreeB1) = x(kDeflection1);
  arm(kFreeB2) = x(kDeflection2);
  arm(kFreeB1Dot) = x(kDeflectionRate1);
  arm(kFreeB2Dot) = x(kDeflectionRate2);
  return arm;
}

inline EkfState EkfProcessModel::Derivative(const EkfState& x, const EkfInput& u) const {
  const FreeArmState<double> arm = ArmState(x);
  const FreeArmState<double> arm_dot =
      body_mass_is_state_ ? FreeArmDerivative<double>(ParamsAt(x), params_.arm_stiffness_n_m_rad,
                                                      params_.arm_damping_n_m_s_rad, arm, Force(x, 0), Force(x, 1))
                          : FreeArmDerivative<double>(params_, params_.arm_stiffness_n_m_rad,
                                                      params_.arm_damping_n_m_s_rad, arm, Force(x, 0), Force(x, 1));
  EkfState x_dot = EkfState::Zero();  // the random walks (mu, e, g, r_m) stay 0
  x_dot(kDeflection1) = arm_dot(kFreeB1);
  x_dot(kDeflection2) = arm_dot(kFreeB2);
  x_dot(kPitchRate) = arm_dot(kFreePhiDot);
  x_dot(kDeflectionRate1) = arm_dot(kFreeB1Dot);
  x_dot(kDeflectionRate2) = arm_dot(kFreeB2Dot);
  if (u.body_supported) {
    const Eigen::Vector2d b_ddot = SupportedArmAcceleration<double>(
        params_, x(kDeflection1), x(kDeflection2), x(kDeflectionRate1), x(kDeflectionRate2), Force(x, 0), Force(x, 1));
    x_dot(kPitchRate) = 0.0;
    x_dot(kDeflectionRate1) = b_ddot(0);
    x_dot(kDeflectionRate2) = b_ddot(1);
  }
  for (int i = 0; i < kBirotorRotors; ++i) {
    x_dot(kOmegaIndex[i]) = MotorLagRate(params_, x(kOmegaIndex[i]), u.omega_cmd_rad_s[i]);
  }
  return x_dot;
}

inline DynamicMatrix EkfProcessModel::Jacobian(const EkfState& x, const EkfInput& u, AccelerometerLinearization* accel,
                                               DynamicVector* mass_column) const {
  if (mass_column != nullptr) mass_column->setZero();
  if (u.body_supported) {
    if (accel != nullptr) accel->valid = false;
    return SupportedJacobian(x);
  }
  double d_accel_d_mass = 0.0;
  if (body_mass_is_state_ && (mass_column != nullptr || accel != nullptr)) {
    DynamicVector column;
    d_accel_d_mass = MassDerivative(x, &column);
    if (mass_column != nullptr) *mass_column = column;
  }
  // Jets over 0..4 = b1, b2, phi_dot, b1_dot, b2_dot, 5, 6 = f1, f2 and a
  // padding (4 SSE packets) through the terms of thesis eq. 3.10; the solve
  // differentiated by hand, d(M^-1 r) = M^-1 (dr - dM M^-1 r), on doubles
  // (the Jacobian of Jets through GeneralizedAcceleration at a third of the cost).
  constexpr int kJetSize = 8;
  using Jet = ceres::Jet<double, kJetSize>;
  Coords<Jet> q, v;
  q << Jet(0.0), Jet(0.0), Jet(0.0), Jet(x(kDeflection1), 0), Jet(x(kDeflection2), 1);
  v << Jet(0.0), Jet(0.0), Jet(x(kPitchRate), 2), Jet(x(kDeflectionRate1), 3), Jet(x(kDeflectionRate2), 4);
  const DynamicsTerms<Jet> terms =
      body_mass_is_state_ ? ComputeDynamicsTerms<Jet>(ParamsAt(x), q, v, Jet(Force(x, 0), 5), Jet(Force(x, 1), 6))
                          : ComputeDynamicsTerms<Jet>(params_, q, v, Jet(Force(x, 0), 5), Jet(Force(x, 1), 6));
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
  // dM is zero outside the entries that couple x, z with phi, b_i (MassEntryVaries).
  for (int i = 0; i < kNumCoordinates; ++i) {
    for (int j = 0; j < kNumCoordinates; ++j) {
      if (MassEntryVaries(i, j)) d_rhs.row(i) -= terms.mass(i, j).v.transpose() * acc_full(j);
    }
  }
  // d_acc = L^-T L^-1 d_rhs on whole rows (8 independent columns; Eigen's 5 x 8 solve is a blocked GEMM).
  const CoordMatrix<double>& l = llt.matrixLLT();  // L in the lower triangle
  Eigen::Matrix<double, kNumCoordinates, kJetSize, Eigen::RowMajor> d_acc = d_rhs;
  for (int i = 0; i < kNumCoordinates; ++i) {
    for (int k = 0; k < i; ++k) d_acc.row(i) -= l(i, k) * d_acc.row(k);
    d_acc.row(i) /= l(i, i);
  }
  for (int i = kNumCoordinates - 1; i >= 0; --i) {
    for (int k = i + 1; k < kNumCoordinates; ++k) d_acc.row(i) -= l(k, i) * d_acc.row(k);
    d_acc.row(i) /= l(i, i);
  }

  constexpr EkfIndex kJetState[5] = {kDeflection1, kDeflection2, kPitchRate, kDeflectionRate1, kDeflectionRate2};
  constexpr EkfIndex kAccRow[3] = {kPitchRate, kDeflectionRate1, kDeflectionRate2};
  constexpr Coordinate kAccCoordinate[3] = {kPhi, kB1, kB2};
  DynamicMatrix a = DynamicMatrix::Zero();
  a(kDeflection1, kDeflectionRate1) = 1.0;
  a(kDeflection2, kDeflectionRate2) = 1.0;
  const Eigen::Vector2d grad[kBirotorRotors] = {ForceGradient(x, 0), ForceGradient(x, 1)};  // (df/domega, df/dmu)
  for (int r = 0; r < 3; ++r) {
    const int row = kAccCoordinate[r];
    for (int c = 0; c < 5; ++c) a(kAccRow[r], kJetState[c]) = d_acc(row, c);
    for (int i = 0; i < kBirotorRotors; ++i) {
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
    for (int i = 0; i < kBirotorRotors; ++i) {
      accel->h(kOmegaIndex[i]) = d_acc(kZ, 5 + i) * grad[i](0);
      accel->h(kThrustScaleIndex[i]) = d_acc(kZ, 5 + i) * grad[i](1);
    }
    accel->h(kBodyMassScale) = d_accel_d_mass;
  }
  return a;
}

inline double EkfProcessModel::MassDerivative(const EkfState& x, DynamicVector* column) const {
  const FreeArmState<double> arm = ArmState(x);
  constexpr double kStep = 1e-4;  // of r_m; truncation ~1e-8 relative, round-off ~1e-12
  FreeArmState<double> arm_dot[kBirotorRotors];
  Eigen::Vector2d specific_force[kBirotorRotors];
  for (int side = 0; side < 2; ++side) {
    BirotorParams p = params_;
    p.body_mass_kg *= x(kBodyMassScale) + (side == 0 ? kStep : -kStep);
    arm_dot[side] = FreeArmDerivative<double>(p, params_.arm_stiffness_n_m_rad, params_.arm_damping_n_m_s_rad, arm,
                                              Force(x, 0), Force(x, 1), &specific_force[side]);
  }
  const double inv = 1.0 / (2.0 * kStep);
  column->setZero();
  (*column)(kPitchRate) = (arm_dot[0](kFreePhiDot) - arm_dot[1](kFreePhiDot)) * inv;
  (*column)(kDeflectionRate1) = (arm_dot[0](kFreeB1Dot) - arm_dot[1](kFreeB1Dot)) * inv;
  (*column)(kDeflectionRate2) = (arm_dot[0](kFreeB2Dot) - arm_dot[1](kFreeB2Dot)) * inv;
  return (specific_force[0](1) - specific_force[1](1)) * inv;
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
  const Eigen::Vector2d grad[kBirotorRotors] = {ForceGradient(x, 0), ForceGradient(x, 1)};  // (df/domega, df/dmu)
  for (int r = 0; r < 2; ++r) {
    const int row = kDeflectionRateIndex[r];
    for (int c = 0; c < 4; ++c) a(row, kJetState[c]) = acc(r).v(c);
    for (int i = 0; i < kBirotorRotors; ++i) {
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

inline DynamicVector EkfProcessModel::ParameterTransition(const DynamicMatrix& a, const DynamicVector& c, double dt_s) {
  const DynamicMatrix a_dt = a * dt_s;
  DynamicVector w = c + a_dt.lazyProduct(c) * 0.25;  // lazyProduct: not Eigen's GEMV call at 9x9
  DynamicVector temp;
  temp.noalias() = a_dt.lazyProduct(w);
  w = c + temp * (1.0 / 3.0);
  temp.noalias() = a_dt.lazyProduct(w);
  return (c + temp * 0.5) * dt_s;
}

inline AccelerometerMeasurementModel::Linearization AccelerometerMeasurementModel::Linearize(
    const EkfProcessModel& process, const EkfState& x) {
  constexpr int kJetSize = 8;  // 7 variables and one of padding (vectorises)
  using Jet = ceres::Jet<double, kJetSize>;
  const BirotorParams params = process.ParamsAt(x);
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
  for (int i = 0; i < kBirotorRotors; ++i) {
    const Eigen::Vector2d grad = process.ForceGradient(x, i);  // (df/domega, df/dmu)
    out.jacobian(0, kOmegaIndex[i]) = a_z.v(5 + i) * grad(0);
    out.jacobian(0, kThrustScaleIndex[i]) = a_z.v(5 + i) * grad(1);
  }
  if (process.body_mass_is_state()) {
    DynamicVector unused;
    out.jacobian(0, kBodyMassScale) = process.MassDerivative(x, &unused);
  }
  out.predicted(0) = a_z.a;
  return out;
}

}  // namespace birotor
