// The thesis's middle steps: the linear force model (observable part of
// thesis eq. 4.2), the Luenberger observer's stable error dynamics (thesis
// eq. 5.7, discrete), why the thesis's identity gain could not work, and both
// the observer and the linear Kalman filter recovering forces.
#include "estimator/linear_force_estimator.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "estimator/luenberger_gain.h"
#include "model/equilibrium.h"
#include "model/linearization.h"
#include "model/plant.h"
#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace {

using testing_support::ForceMae;
using testing_support::ReferenceConfig;
using testing_support::RunScenario;
using testing_support::ScenarioFile;
using testing_support::ScenarioRun;

// Eigenvalues through Eigen's dynamic-size solver: one instantiation of
// EigenSolver serves the 7, 10 and 12-state matrices of this file, where a
// fixed-size instantiation costs ~10 s of compile time each
// (docs/development.md, build time).
Eigen::VectorXcd EigenvaluesOf(const Eigen::MatrixXd& matrix) { return matrix.eigenvalues(); }

LinearForceModel ReferenceModel() { return BuildLinearForceModel(BirotorParams(), EkfOptions(), LinearModelOptions()); }

TEST(LinearForceModel, IsTheObservableBlockOfTheAugmentedModel) {
  const LinearForceModel model = ReferenceModel();
  // reference-vehicle.md: d(b1_ddot)/d(f1) = -13.883, d(b1_ddot)/d(b1) = -2.0901e5, d(b1_ddot)/d(b2) = -4.2048e4.
  EXPECT_NEAR(model.a_continuous(kLinDeflectionRate1, kLinForce1), -13.883, 1e-3);
  EXPECT_NEAR(model.a_continuous(kLinDeflectionRate1, kLinDeflection1), -2.0901e5, 10.0);
  EXPECT_NEAR(model.a_continuous(kLinDeflectionRate1, kLinDeflection2), -4.2048e4, 10.0);
  EXPECT_EQ(model.a_continuous(kLinDeflection1, kLinDeflectionRate1), 1.0);
  // Forces are random walks (thesis eq. 4.2: zero rows).
  EXPECT_EQ(model.a_continuous.row(kLinForce1).norm(), 0.0);
  EXPECT_EQ(model.a_continuous.row(kLinForce2).norm(), 0.0);
  // Hover (reference-vehicle.md): 22.4465 N, b1 = -0.0018664 rad.
  EXPECT_NEAR(model.force_hover_n[0], 22.4465, 1e-3);
  EXPECT_NEAR(model.deflection_hover_rad[0], -0.0018664, 1e-7);
  // Force noise: linear_model.force_psd_n2_s.
  EXPECT_EQ(model.force_psd_n2_s, LinearModelOptions().force_psd_n2_s);
  // phi_dot is driven by b1 + b2 only (reference-vehicle.md: d(phi_ddot)/d(b_i) = 5.256e4) and drives nothing.
  EXPECT_NEAR(model.a_continuous(kLinPitchRate, kLinDeflection1), 5.256e4, 1.0);
  EXPECT_EQ(model.a_continuous.col(kLinPitchRate).norm(), 0.0);
}

TEST(LinearForceModel, DiscretisationIsTheMatrixExponential) {
  const LinearForceModel model = ReferenceModel();
  // Sampling a constant force: the discrete and the continuous model agree
  // on the static deflection, b = -A_bb^-1 A_bf f (fixed point of A_d).
  LinearState x = LinearState::Zero();
  x(kLinForce1) = 1.0;
  x(kLinForce2) = 1.0;
  const Eigen::Matrix2d a_bb = model.a_continuous.block<2, 2>(kLinDeflectionRate1, kLinDeflection1);
  const Eigen::Matrix2d a_bf = model.a_continuous.block<2, 2>(kLinDeflectionRate1, kLinForce1);
  x.head<2>() = -a_bb.inverse() * a_bf * x.segment<2>(kLinForce1);
  const LinearState next = model.a_discrete * x;
  EXPECT_LT((next - x).cwiseQuotient(model.scale).cwiseAbs().maxCoeff(), 1e-9);
  // Q_d ~ Q_c T on the forces (random walk) [N^2].
  EXPECT_NEAR(model.noise_discrete(kLinForce1, kLinForce1), model.force_psd_n2_s * model.period_s, 1e-12);
}

TEST(LuenbergerObserver, ErrorDynamicsAreStableWithThePlacedPoles) {
  const LinearForceModel model = ReferenceModel();
  const LuenbergerOptions options;
  const ObserverGains gains = PlaceObserverPoles(model, options);
  const Eigen::VectorXcd eigenvalues = EigenvaluesOf(ObserverErrorMatrix(model, gains));
  // Thesis eq. 5.8 in discrete time: e[k] = ((I - L C) A_d)^k e[0] decays iff
  // every eigenvalue is inside the unit circle.
  EXPECT_LT(eigenvalues.cwiseAbs().maxCoeff(), 1.0);
  // The slowest are the force and phi_dot poles exp(-2 pi 30 Hz 1 ms) = 0.8282.
  EXPECT_NEAR(eigenvalues.cwiseAbs().maxCoeff(), 0.8282, 1e-4);
  // And they are the placed poles.
  for (const std::complex<double>& pole : DesiredObserverPoles(model, options)) {
    double nearest = 1e9;
    for (int i = 0; i < eigenvalues.size(); ++i) nearest = std::min(nearest, std::abs(eigenvalues(i) - pole));
    EXPECT_LT(nearest, 1e-6) << pole;
  }
  // The open arm modes (65 Hz, 80 Hz, damping 0.02) are now damped at 0.7:
  // |z| = exp(-0.7 w_n T) < 0.8 for them.
  int fast = 0;
  for (int i = 0; i < eigenvalues.size(); ++i) fast += std::abs(eigenvalues(i)) < 0.8;
  EXPECT_EQ(fast, 4);
}

TEST(LuenbergerObserver, TheThesisIdentityGainNeverCorrectsTheForces) {
  // Thesis section 5.4.2: K = I with C selecting the ten mechanical states
  // (eq. 4.3), i.e. K = [I_10; 0]. The force rows of K are zero, so
  // A~ - K C~ = [[A - I, B], [0, 0]]: two eigenvalues exactly 0 (the force
  // errors never change: the forces are not estimated at all), the others
  // those of A shifted by -1: the rigid-body errors decay at only 1/s and the
  // arm errors at 9-13/s against their 410-500 rad/s oscillation.
  const LinearModel linear = LinearizeAtHover(BirotorParams());
  const AugMatrix a = AugmentWithForces(linear);
  Eigen::Matrix<double, kMechStateSize, kAugStateSize> c = Eigen::Matrix<double, kMechStateSize, kAugStateSize>::Zero();
  c.leftCols<kMechStateSize>().setIdentity();
  Eigen::Matrix<double, kAugStateSize, kMechStateSize> k = Eigen::Matrix<double, kAugStateSize, kMechStateSize>::Zero();
  k.topRows<kMechStateSize>().setIdentity();
  const AugMatrix error = a - k * c;
  EXPECT_EQ(error.row(kAugForce1).norm(), 0.0);
  EXPECT_EQ(error.row(kAugForce2).norm(), 0.0);
  const Eigen::VectorXcd eigenvalues = EigenvaluesOf(error);
  const Eigen::VectorXcd open_loop = EigenvaluesOf(linear.a);
  int zero = 0;
  double slowest_decay = -1e9;
  for (int i = 0; i < eigenvalues.size(); ++i) {
    if (std::abs(eigenvalues(i)) < 1e-9) {
      ++zero;
      continue;
    }
    slowest_decay = std::max(slowest_decay, eigenvalues(i).real());
    double nearest = 1e9;
    for (int j = 0; j < open_loop.size(); ++j) {
      nearest = std::min(nearest, std::abs(eigenvalues(i) - (open_loop(j) - 1.0)));
    }
    EXPECT_LT(nearest, 1e-6 * std::abs(eigenvalues(i)));
  }
  EXPECT_NEAR(slowest_decay, -1.0, 1e-6);
  EXPECT_EQ(zero, 2);
}

// Nonlinear plant (estimator/plant.h, the simulator's equations) from hover
// with constant rotor commands: after the 35 ms motor lag the forces are
// constant. Strain every 1 ms, motor commands and exact telemetry every 2 ms.
struct ConstantForceRun {
  double mean_abs_error_n[2] = {0, 0};  // over the last 0.5 s
  double thrust_scale[2] = {0, 0};      // last estimate
  double force_std_n[2] = {0, 0};
  int32_t status = 0;
};

ConstantForceRun RunConstantForces(const std::string& method, double force1_n, double force2_n) {
  EstimatorConfig config;
  config.method = method;
  EstimatorPipeline pipeline(config);
  const BirotorParams p = BirotorModelOf(config.vehicle);
  const Equilibrium eq = SolveHoverEquilibrium(p);
  PlantState x = HoverPlantState(eq);
  PlantInput u;
  u.omega_cmd_rad_s[0] = std::sqrt(force1_n / p.thrust_coeff_n_s2_rad2);
  u.omega_cmd_rad_s[1] = std::sqrt(force2_n / p.thrust_coeff_n_s2_rad2);
  ConstantForceRun run;
  int scored = 0;
  constexpr int kSubsteps = 4;  // 0.25 ms RK4 steps, as the simulator
  for (int k = 0; k < 1500; ++k) {
    const int64_t utime = 1000000 + k * 1000;
    if (k % 2 == 0) {
      MotorSample m;
      m.utime = utime;
      m.seq = k / 2;
      for (int i = 0; i < 2; ++i) {
        m.omega_cmd_rad_s[i] = u.omega_cmd_rad_s[i];
        m.omega_meas_rad_s[i] = x(kPlantOmega1 + i);
      }
      pipeline.OnMotor(m);
    }
    StrainSample s;
    s.utime = utime;
    s.seq = k;
    s.deflection_rad[0] = x(kPlantQ + kB1);
    s.deflection_rad[1] = x(kPlantQ + kB2);
    ForceEstimate e;
    EXPECT_TRUE(pipeline.OnStrain(s, &e));
    if (k >= 1000) {
      for (int i = 0; i < 2; ++i) {
        run.mean_abs_error_n[i] += std::abs(e.force_n[i] - RotorThrust(p, x(kPlantOmega1 + i), 1.0));
      }
      ++scored;
    }
    for (int i = 0; i < 2; ++i) {
      run.thrust_scale[i] = e.thrust_scale[i];
      run.force_std_n[i] = e.force_std_n[i];
    }
    run.status = e.status;
    for (int j = 0; j < kSubsteps; ++j) x = StepPlant(p, x, u, 1e-3 / kSubsteps);
  }
  for (double& mae : run.mean_abs_error_n) mae /= scored;
  return run;
}

class ConstantForces : public testing::TestWithParam<const char*> {};

TEST_P(ConstantForces, RecoveredFromTheNonlinearPlant) {
  // 1.55 N above hover on both rotors (a climb), then 1 N apart (a pitch-up).
  for (const auto& forces : {std::pair<double, double>{24.0, 24.0}, std::pair<double, double>{23.0, 22.0}}) {
    const ConstantForceRun run = RunConstantForces(GetParam(), forces.first, forces.second);
    for (int i = 0; i < 2; ++i) {
      RecordProperty("mae_n", std::to_string(run.mean_abs_error_n[i]));
      EXPECT_LT(run.mean_abs_error_n[i], 0.005) << GetParam() << " rotor " << i + 1;
      EXPECT_NEAR(run.thrust_scale[i], 1.0, 0.001);
    }
    EXPECT_TRUE(run.status & kStatusValid);
  }
}

INSTANTIATE_TEST_SUITE_P(LinearMethods, ConstantForces, testing::Values("luenberger", "linear_kf"));

const std::vector<std::string> kNoiseFree = {"sensors.strain.noise_rad=0",      "sensors.motor.speed_noise_rad_s=0",
                                             "sensors.imu.gyro_noise_rad_s=0",  "sensors.imu.accel_noise_m_s2=0",
                                             "sensors.pose.position_noise_m=0", "sensors.pose.angle_noise_rad=0",
                                             "vehicle.turbulence_std=0"};

class NoiseFreeGentle : public testing::TestWithParam<const char*> {};

TEST_P(NoiseFreeGentle, BelowFiveMillinewtons) {
  // Issue 15 target: noise-free `gentle` (thesis test 2) below 0.005 N MAE.
  const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile("gentle"), kNoiseFree), ReferenceConfig(GetParam()));
  for (int i = 0; i < 2; ++i) {
    const double mae = ForceMae(run, i, 500000);
    RecordProperty("mae_n", std::to_string(mae));
    EXPECT_LT(mae, 0.005) << GetParam() << " rotor " << i + 1;
  }
  EXPECT_EQ(run.non_finite, 0);
}

INSTANTIATE_TEST_SUITE_P(LinearMethods, NoiseFreeGentle, testing::Values("luenberger", "linear_kf"));

TEST(LinearKalmanFilter, WithinTenPercentOfTheEkfInHover) {
  // Issue 15 target, reference noise, `hover` (20 s), first 0.5 s not scored,
  // against the EKF on the same inputs: the linear methods have no
  // accelerometer and no gauge offset states (with both the EKF is 6 %
  // better again: 0.067 N, README).
  const Scenario hover = LoadScenario(ScenarioFile("hover"));
  EstimatorConfig same_inputs = ReferenceConfig("ekf");
  same_inputs.ekf.use_accelerometer = false;
  same_inputs.ekf.estimate_gauge_offsets = false;
  const ScenarioRun ekf = RunScenario(hover, same_inputs);
  const ScenarioRun linear = RunScenario(hover, ReferenceConfig("linear_kf"));
  for (int i = 0; i < 2; ++i) {
    const double ekf_mae = ForceMae(ekf, i, 500000), linear_mae = ForceMae(linear, i, 500000);
    RecordProperty("ekf_mae_n", std::to_string(ekf_mae));
    RecordProperty("linear_kf_mae_n", std::to_string(linear_mae));
    EXPECT_LT(linear_mae, 1.1 * ekf_mae) << "rotor " << i + 1;
  }
}

TEST(LinearKalmanFilter, CovarianceConvergesToTheSteadyState) {
  // A time-varying Kalman filter on a time-invariant model: after a few
  // seconds the covariance is the fixed point of the Riccati recursion
  // P = A (P - P C^T S^-1 C P) A^T + Q, whatever the start.
  EstimatorConfig config;
  LinearForceEstimator filter(BirotorModelOf(config.vehicle), config.ekf, config.linear_model);
  const LinearForceModel& model = filter.model();
  StrainSample s;
  ForceEstimate e;
  StrainStepInfo info;
  for (int k = 0; k < 5000; ++k) {
    s.utime = k * 1000;
    s.deflection_rad[0] = model.deflection_hover_rad[0];
    s.deflection_rad[1] = model.deflection_hover_rad[1];
    filter.AddStrain(s, &e, &info, nullptr);
  }
  const LinearMatrix p = filter.covariance();
  const LinearMatrix prior = model.a_discrete * p * model.a_discrete.transpose() + model.noise_discrete;
  Eigen::Matrix2d innovation = model.c * prior * model.c.transpose();
  innovation.diagonal().array() += config.ekf.strain_noise_rad * config.ekf.strain_noise_rad;
  const LinearMatrix posterior = prior - prior * model.c.transpose() * innovation.inverse() * model.c * prior;
  EXPECT_NEAR(posterior(kLinForce1, kLinForce1), p(kLinForce1, kLinForce1), 1e-9 * p(kLinForce1, kLinForce1));
  EXPECT_NEAR(e.force_std_n[0], std::sqrt(p(kLinForce1, kLinForce1)), 1e-12);
}

}  // namespace
}  // namespace birotor
