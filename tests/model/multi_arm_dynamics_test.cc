// The N-arm Euler-Lagrange model: the birotor's closed form at N = 2, the
// accelerations solving M a = tau - C - G, and energy conservation.
#include "model/multi_arm_dynamics.h"

#include <gtest/gtest.h>

#include <random>

#include "model/rk4.h"
#include "tests/model/test_vehicles.h"

namespace birotor {
namespace {

using test_vehicles::Birotor;
using test_vehicles::Trirotor;

MultiCoords<double> RandomCoords(int n, std::mt19937* rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  MultiCoords<double> out(n);
  for (int i = 0; i < n; ++i) out(i) = u(*rng);
  return out;
}

TEST(MultiArmDynamics, BirotorEqualsClosedFormOfBirotorDynamics) {
  const BirotorParams params;
  const VehicleDescription vehicle = Birotor(params);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> force(0.0, 40.0);
  for (int trial = 0; trial < 200; ++trial) {
    const MultiCoords<double> q = RandomCoords(5, &rng, 1.0), v = RandomCoords(5, &rng, 3.0);
    ArmForces<double> f(2);
    f << force(rng), force(rng);
    const MultiArmTerms<double> ours = ComputeMultiArmTerms<double>(vehicle, q, v, f);
    const DynamicsTerms<double> reference =
        ComputeDynamicsTerms<double>(params, Coords<double>(q), Coords<double>(v), f(0), f(1));
    EXPECT_LT((ours.mass - reference.mass).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((ours.coriolis - reference.coriolis).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((ours.gravity_spring - reference.gravity_spring).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((ours.generalized_thrust - reference.generalized_thrust).cwiseAbs().maxCoeff(), 1e-12);
    const MultiCoords<double> a = MultiArmAcceleration<double>(vehicle, q, v, f);
    const Coords<double> a_ref =
        GeneralizedAcceleration<double>(params, Coords<double>(q), Coords<double>(v), f(0), f(1));
    EXPECT_LT((a - a_ref).cwiseAbs().maxCoeff(), 1e-9 * std::max(1.0, a_ref.cwiseAbs().maxCoeff()));
  }
}

TEST(MultiArmDynamics, AccelerationSolvesTheEquationsOfMotion) {
  const VehicleDescription vehicle = Trirotor();
  std::mt19937 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const MultiCoords<double> q = RandomCoords(6, &rng, 1.0), v = RandomCoords(6, &rng, 3.0);
    ArmForces<double> f(3);
    f << 27.0, 17.0, 16.0;
    const MultiArmTerms<double> t = ComputeMultiArmTerms<double>(vehicle, q, v, f);
    const MultiCoords<double> a = MultiArmAcceleration<double>(vehicle, q, v, f);
    const MultiCoords<double> rhs = t.generalized_thrust - t.coriolis - t.gravity_spring;
    EXPECT_LT((t.mass * a - rhs).cwiseAbs().maxCoeff(), 1e-9 * std::max(1.0, rhs.cwiseAbs().maxCoeff()));
    EXPECT_EQ((t.mass - t.mass.transpose()).cwiseAbs().maxCoeff(), 0.0);
  }
}

// With no thrust and d_i = 0 the energy T + U is a constant of the motion; RK4
// at dt = 1e-5 s (0.3 % of the fastest arm period) over 0.5 s keeps it to the
// bound below (measured 2.93e-12 J of |E| = 5.33 J on the shipped trirotor; bound 1.5x).
TEST(MultiArmDynamics, EnergyConservedWithoutThrustAndDamping) {
  VehicleDescription vehicle = Trirotor();
  for (int i = 0; i < vehicle.arm_count; ++i) vehicle.arms[static_cast<size_t>(i)].damping_n_m_s_rad = 0.0;
  using State = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 2 * kMaxCoordinates, 1>;
  const int n = CoordinateCount(vehicle);
  State x(2 * n);
  x << 0.1, -0.2, 0.3, 0.01, -0.02, 0.015, 0.5, 1.0, -2.0, 0.5, 0.3, -0.4;
  const ArmForces<double> no_thrust = ArmForces<double>::Zero(vehicle.arm_count);
  const auto derivative = [&](const State& s) {
    State ds(2 * n);
    ds.head(n) = s.tail(n);
    ds.tail(n) = MultiArmAcceleration<double>(vehicle, MultiCoords<double>(s.head(n)), MultiCoords<double>(s.tail(n)),
                                              no_thrust);
    return ds;
  };
  const double e0 = MultiArmEnergy<double>(vehicle, MultiCoords<double>(x.head(n)), MultiCoords<double>(x.tail(n)));
  double worst_j = 0;
  for (int step = 0; step < 50000; ++step) {
    x = Rk4Step(x, 1e-5, derivative);
    const double e = MultiArmEnergy<double>(vehicle, MultiCoords<double>(x.head(n)), MultiCoords<double>(x.tail(n)));
    worst_j = std::max(worst_j, std::abs(e - e0));
  }
  EXPECT_LT(x(kZ), -0.9);  // z(0.5 s) = -0.2 + 0.5 - g / 8 = -0.93 m: gravity did work
  EXPECT_LT(worst_j, 4.4e-12) << "E0 = " << e0 << " J";
}

}  // namespace
}  // namespace birotor
