// The free-body model of the N-arm flight residual
// (identification/multi_arm_flight_residual.h) against the N-arm dynamics
// it is built from (model/multi_arm_dynamics.h): its rows phi, b at phi = 0
// and zero body velocity are those of MultiArmAcceleration at any phi and
// body velocity, its specific force the body-frame one, and its fitted k_i
// and m_p,i those of a description that carries them.
#include "identification/multi_arm_flight_residual.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

std::string SourcePath(const std::string& relative) { return std::string(BIROTOR_SOURCE_DIR) + "/" + relative; }

struct FreeBodyCase {
  FlightState<double> x;
  ArmForces<double> force_n;
};

// A tilted, moving trirotor state: phi_dot 0.7 rad/s, deflections and
// rates of a few mrad, thrusts near hover.
FreeBodyCase TrirotorCase() {
  FreeBodyCase c{FlightState<double>(FlightStateSize(3)), ArmForces<double>(3)};
  c.x << 0.7, 2.1e-3, -1.3e-3, 1.7e-3, 0.05, -0.08, 0.03;
  c.force_n << 27.0, 15.1, 13.4;
  return c;
}

// MultiArmAcceleration of `vehicle` at tilt phi and body velocity (vx, vz)
// with the case's phi_dot, deflections and rates.
MultiCoords<double> FullAcceleration(const VehicleDescription& vehicle, const FreeBodyCase& c, double phi, double vx,
                                     double vz) {
  const int n = vehicle.arm_count;
  MultiCoords<double> q = MultiCoords<double>::Zero(CoordinateCount(vehicle));
  MultiCoords<double> v = MultiCoords<double>::Zero(CoordinateCount(vehicle));
  q(kPhi) = phi;
  q(kX) = 3.0;
  q(kZ) = -1.0;
  v(kX) = vx;
  v(kZ) = vz;
  v(kPhi) = c.x(0);
  for (int i = 0; i < n; ++i) {
    q(DeflectionIndex(i)) = c.x(FlightDeflectionIndex(i));
    v(DeflectionIndex(i)) = c.x(FlightRateIndex(n, i));
  }
  return MultiArmAcceleration<double>(vehicle, q, v, c.force_n);
}

MultiArmFlightWindowResidual::Parameters<double> FileParameters(const VehicleDescription& vehicle) {
  const int n = vehicle.arm_count;
  MultiArmFlightWindowResidual::Parameters<double> p{ArmForces<double>(n), ArmForces<double>(n), ArmForces<double>(n)};
  for (int i = 0; i < n; ++i) {
    p.stiffness(i) = vehicle.arms[static_cast<size_t>(i)].stiffness_n_m_rad;
    p.thrust_coeff(i) = vehicle.arms[static_cast<size_t>(i)].thrust_coeff_n_s2_rad2;
    p.tip_mass_ratio(i) = 1.0;
  }
  return p;
}

const MultiArmFlightWindowResidual::Noise kNoise{2e-5, 5e-3, 5e-2, 3.0};

TEST(MultiArmFlightResidualTest, FreeBodyRowsAreThoseOfTheFullDynamicsAtAnyTiltAndBodyVelocity) {
  const VehicleDescription trirotor = LoadVehicleDescription(SourcePath("config/vehicles/trirotor.yaml"));
  const MultiArmFlightWindowResidual residual(trirotor, {}, kNoise, 1, false);
  const FreeBodyCase c = TrirotorCase();
  Eigen::Matrix<double, 2, 1> specific_force;
  const FlightState<double> rate =
      residual.Derivative<double>(c.x, FileParameters(trirotor), c.force_n, &specific_force);
  for (const double phi : {0.0, 0.4, -1.1}) {
    const MultiCoords<double> full = FullAcceleration(trirotor, c, phi, 1.5, -0.6);
    // Uniform gravity and a plane without a preferred direction: rounding only.
    EXPECT_NEAR(rate(0), full(kPhi), 1e-9 * std::abs(full(kPhi)) + 1e-9) << "phi " << phi;
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(rate(FlightDeflectionIndex(i)), c.x(FlightRateIndex(3, i)));
      EXPECT_NEAR(rate(FlightRateIndex(3, i)), full(DeflectionIndex(i)), 1e-9 * std::abs(full(DeflectionIndex(i))))
          << "phi " << phi << " arm " << i + 1;
    }
    // The accelerometer: R(-phi) (p_ddot + g e_z), body frame (simulator/body_sensors.h).
    const double ax = full(kX), az = full(kZ) + trirotor.gravity_m_s2;
    EXPECT_NEAR(specific_force(0), std::cos(phi) * ax + std::sin(phi) * az, 1e-9) << "phi " << phi;
    EXPECT_NEAR(specific_force(1), -std::sin(phi) * ax + std::cos(phi) * az, 1e-9) << "phi " << phi;
  }
}

TEST(MultiArmFlightResidualTest, FittedStiffnessAndTipMassAreThoseOfADescriptionCarryingThem) {
  const VehicleDescription file = LoadVehicleDescription(SourcePath("config/vehicles/trirotor.yaml"));
  const VehicleDescription truth = LoadVehicleDescription(SourcePath("tests/data/trirotor_modified.yaml"));
  // The file's damping in both: d is not a parameter of the residual.
  VehicleDescription changed = truth;
  for (size_t i = 0; i < 3; ++i) changed.arms[i].damping_n_m_s_rad = file.arms[i].damping_n_m_s_rad;
  const MultiArmFlightWindowResidual residual(file, {}, kNoise, 1, true);
  MultiArmFlightWindowResidual::Parameters<double> p = FileParameters(changed);
  for (int i = 0; i < 3; ++i) {
    p.tip_mass_ratio(i) =
        changed.arms[static_cast<size_t>(i)].tip_mass_kg / file.arms[static_cast<size_t>(i)].tip_mass_kg;
  }
  const FreeBodyCase c = TrirotorCase();
  Eigen::Matrix<double, 2, 1> specific_force;
  const FlightState<double> rate = residual.Derivative<double>(c.x, p, c.force_n, &specific_force);
  const MultiCoords<double> full = FullAcceleration(changed, c, 0.0, 0.0, 0.0);
  EXPECT_NEAR(rate(0), full(kPhi), 1e-9 * std::abs(full(kPhi)));
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(rate(FlightRateIndex(3, i)), full(DeflectionIndex(i)), 1e-9 * std::abs(full(DeflectionIndex(i))))
        << "arm " << i + 1;
  }
  EXPECT_NEAR(specific_force(1), full(kZ) + file.gravity_m_s2, 1e-9);
  // And the file's own terms differ by far more than that (the check has teeth).
  const MultiCoords<double> unchanged = FullAcceleration(file, c, 0.0, 0.0, 0.0);
  EXPECT_GT(std::abs(unchanged(DeflectionIndex(2)) - full(DeflectionIndex(2))), 1.0);
}

}  // namespace
}  // namespace birotor
