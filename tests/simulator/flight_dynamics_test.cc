// Tests of simulator/flight_dynamics.h: the simulator's derivative equals the
// model's PlantDerivative (model/plant.h) up to rounding.
#include "simulator/flight_dynamics.h"

#include <gtest/gtest.h>

#include "model/equilibrium.h"

namespace birotor {
namespace {

TEST(FlightDynamicsTest, MatchesPlantDerivativeAwayFromHover) {
  const VehicleParams p;
  PlantState x;
  x << 0.3, -0.2, 0.25, -0.004, 0.003, 0.5, -0.4, 1.2, 0.3, -0.2, 650.0, 760.0;
  PlantInput u;
  u.omega_cmd_rad_s[0] = 700.0;
  u.omega_cmd_rad_s[1] = 1300.0;  // clamped
  u.thrust_scale[0] = 0.9;
  u.thrust_scale[1] = 1.02;
  const PlantState expected = PlantDerivative(p, x, u);
  const PlantState actual = FlightDerivative(p, x, u);
  for (int i = 0; i < kPlantStateSize; ++i)
    EXPECT_NEAR(actual(i), expected(i), 1e-10 * (1.0 + std::abs(expected(i)))) << i;
}

TEST(FlightDynamicsTest, HoverEquilibriumIsAFixedPoint) {
  const VehicleParams p;
  const Equilibrium eq = SolveHoverEquilibrium(p);
  PlantState x = PlantState::Zero();
  x(kPlantQ + kB1) = eq.deflection_rad[0];
  x(kPlantQ + kB2) = eq.deflection_rad[1];
  x(kPlantOmega1) = eq.omega_rad_s[0];
  x(kPlantOmega2) = eq.omega_rad_s[1];
  PlantInput u;
  u.omega_cmd_rad_s[0] = eq.omega_rad_s[0];
  u.omega_cmd_rad_s[1] = eq.omega_rad_s[1];
  EXPECT_LT(FlightDerivative(p, x, u).cwiseAbs().maxCoeff(), 1e-8);
}

}  // namespace
}  // namespace birotor
