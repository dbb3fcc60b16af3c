// The parameter-augmented hover linearisation (model/parameter_observability.h)
// on the reference vehicle: Jacobian columns against the physics they stand
// for, and which slow parameters the EKF's measurements determine with and
// without the accelerometer (issue 27 item 2; birotor-analyze prints the same).
#include "model/parameter_observability.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "model/equilibrium.h"

namespace birotor {
namespace {

using M = ParameterMeasurement;

int Index(const std::string& name) {
  const auto& names = ParameterAugmentedStateNames();
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

TEST(ParameterObservability, ColumnsAreThePhysics) {
  const BirotorParams p;  // the reference vehicle
  Eigen::MatrixXd a, c;
  LinearizeWithParameters(p, {M::kStrain, M::kAccelerometer}, &a, &c);
  ASSERT_EQ(a.rows(), kParameterAugmentedSize);
  ASSERT_EQ(c.rows(), 3);
  const Equilibrium eq = SolveHoverEquilibrium(p);
  // Strain row i: d(s_i b_i + o_i)/d theta_si = b_i at hover, d/d o_i = 1.
  EXPECT_NEAR(c(0, Index("s1")), eq.deflection_rad[0], 1e-9);
  EXPECT_NEAR(c(1, Index("o2")), std::fabs(eq.deflection_rad[1]), 1e-9);
  // Accelerometer on the body: z_ddot = (R - m g) / m with the hinge
  // reactions R = m g at hover, so d a_z / d theta_m = -g; the thrust acts
  // on the tips and reaches the body through the hinges, so d a_z / d mu_i = 0.
  EXPECT_NEAR(c(2, Index("m")), -p.gravity_m_s2, 1e-5);
  EXPECT_NEAR(c(2, Index("mu1")), 0.0, 1e-6);
  // Held commands at hover: tau_m has no first-order effect (omega = command).
  EXPECT_NEAR(a.col(Index("tau_m")).norm(), 0.0, 1e-6);
}

// Measured on the reference vehicle (exact ranks of the staircase test; the
// combinations are the reduced row echelon form, docs/mismatch.md).
TEST(ParameterObservability, WithoutTheAccelerometerThreeCombinations) {
  const ParameterObservability r =
      AnalyzeParameterObservability(BirotorParams(), {M::kStrain, M::kTelemetry, M::kGyro});
  EXPECT_EQ(r.report.rank, 10);
  EXPECT_EQ(r.determined, 3);
  EXPECT_TRUE(r.observable_parameters.empty());  // no parameter on its own
  ASSERT_EQ(r.determined_combinations.size(), 3u);
  // mu_i against the strain's force: c_T, the other arm's k, s and o (never tau_m).
  EXPECT_EQ(r.determined_combinations[0], "1.00 mu1 + 1.00 o2 + -1.00 k2 + 0.13 m + -0.13 m_p + 1.00 c_T + 1.00 s2");
  for (const std::string& c : r.determined_combinations) EXPECT_EQ(c.find("tau_m"), std::string::npos) << c;
}

TEST(ParameterObservability, TheAccelerometerAddsTheTotalForceOverTheMass) {
  const ParameterObservability r =
      AnalyzeParameterObservability(BirotorParams(), {M::kStrain, M::kTelemetry, M::kGyro, M::kAccelerometer});
  EXPECT_EQ(r.report.rank, 11);
  EXPECT_EQ(r.determined, 4);
  ASSERT_EQ(r.determined_combinations.size(), 4u);
  // Thrust over weight, per rotor: mu_i c_T against m (0.87) and m_p (0.13),
  // the body's and the tips' shares of the total mass 4.576 kg.
  EXPECT_EQ(r.determined_combinations[0], "1.00 mu1 + -0.87 m + -0.13 m_p + 1.00 c_T");
  EXPECT_EQ(r.determined_combinations[2], "1.00 o1 + 1.00 k1 + -1.00 m + -1.00 s1");
}

}  // namespace
}  // namespace birotor
