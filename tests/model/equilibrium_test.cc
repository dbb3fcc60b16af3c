// Hover equilibrium: the reference-vehicle values of the spec.
#include "model/equilibrium.h"

#include <gtest/gtest.h>

namespace birotor {
namespace {

TEST(Equilibrium, ReproducesReferenceHover) {
  const BirotorParams p;
  const Equilibrium eq = SolveHoverEquilibrium(p);
  ASSERT_TRUE(eq.converged);
  EXPECT_NEAR(eq.force_n[0], 22.4465, 5e-4);
  EXPECT_NEAR(eq.force_n[1], 22.4465, 5e-4);
  EXPECT_NEAR(eq.deflection_rad[0], -0.0018664, 5e-8);
  EXPECT_NEAR(eq.deflection_rad[1], 0.0018664, 5e-8);
  EXPECT_NEAR(eq.omega_rad_s[0], 698.55, 0.01);
  EXPECT_NEAR(p.HoverForceN(), 22.4465, 5e-5);
}

}  // namespace
}  // namespace birotor
