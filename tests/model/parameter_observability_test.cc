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
  const VehicleParams p;  // the reference vehicle
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

TEST(ParameterObservability, WithoutTheAccelerometer) {
  const ParameterObservability r =
      AnalyzeParameterObservability(VehicleParams(), {M::kStrain, M::kTelemetry, M::kGyro});
  for (const auto& h : r.determined_combinations) std::printf("determined: %s\n", h.c_str());
  std::printf("rank %d observable:", r.report.rank);
  for (const auto& s : r.observable_parameters) std::printf(" %s", s.c_str());
  std::printf("\n");
}

TEST(ParameterObservability, WithTheAccelerometer) {
  const ParameterObservability r =
      AnalyzeParameterObservability(VehicleParams(), {M::kStrain, M::kTelemetry, M::kGyro, M::kAccelerometer});
  for (const auto& h : r.determined_combinations) std::printf("determined: %s\n", h.c_str());
  std::printf("rank %d observable:", r.report.rank);
  for (const auto& s : r.observable_parameters) std::printf(" %s", s.c_str());
  std::printf("\n");
}

}  // namespace
}  // namespace birotor
