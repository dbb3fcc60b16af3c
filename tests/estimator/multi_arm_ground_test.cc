// The N-arm EKF on a flight that starts on the ground (issue 38 item 1): the
// held body's process model (estimator/multi_arm_ekf_supported.h) against
// central differences and against the simulator's supported rows
// (model/multi_arm_plant.h), the ground contact of a description
// (estimator/multi_arm_ground.h), and the trirotor and the birotor
// description (N = 2) on gauge_offset and gauge_drift: 3 s at rest with the
// motors stopped, 1 s spool-up, then flight, scored from the lift-off as the
// birotor's eval does. Figures measured on this commit with birotor-eval
// --vehicle (the same code); margins <= 1.5x.
#include "estimator/multi_arm_ground.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "estimator/multi_arm_ekf_model.h"
#include "evaluation/eval_runner.h"
#include "evaluation/multi_arm_accuracy.h"
#include "model/multi_arm_plant.h"
#include "multi_arm_source_files.h"

namespace birotor {
namespace {

using Model = MultiArmEkfModel<3>;
using L = MultiArmEkfLayout<3>;

// A trirotor on the ground at idle: arms bent and swinging, rotors spinning up.
Model::State GroundState() {
  Model::State x = Model::State::Zero();
  for (int i = 0; i < 3; ++i) {
    x(L::Deflection(i)) = -1.0e-4 + 3e-4 * i;
    x(L::DeflectionRate(i)) = 0.04 * (i - 1);
    x(L::Omega(i)) = 300.0 + 25.0 * i;
    x(L::ThrustScale(i)) = 1.0 - 0.05 * i;
    x(L::GaugeOffset(i)) = 1e-5;
  }
  return x;
}

Model::Input Supported() {
  Model::Input u;
  u.omega_cmd_rad_s = {350.0, 320.0, 310.0};
  u.supported = true;
  return u;
}

// A_d of the held body against central differences of its derivative
// (relative step 1e-6: truncation and round-off ~1e-9 of the column scale;
// asserted 1e-6, as the free body's test).
TEST(MultiArmGroundTest, SupportedJacobianMatchesCentralDifferences) {
  const Model model(Vehicle("trirotor"));
  const Model::State x = GroundState();
  const Model::Input u = Supported();
  const Model::DynamicMatrix a = model.Jacobian(x, u);
  for (int c = L::kFirstDynamic; c < Model::kS; ++c) {
    const double h = 1e-6 * std::max(1.0, std::abs(x(c)));
    Model::State plus = x, minus = x;
    plus(c) += h;
    minus(c) -= h;
    const Model::State numeric = (model.Derivative(plus, u) - model.Derivative(minus, u)) / (2.0 * h);
    const double scale = std::max(1.0, numeric.cwiseAbs().maxCoeff());
    for (int r = L::kFirstDynamic; r < Model::kS; ++r) {
      EXPECT_NEAR(a(L::Dynamic(r), L::Dynamic(c)), numeric(r), 1e-6 * scale) << "row " << r << " col " << c;
    }
  }
}

// The filter's held body is the simulator's on the ground: b_ddot_i of
// MultiArmSupportedDerivative at phi = 0 with the same b, b_dot and thrusts
// (two codings of M_bb b_ddot = tau_b - C_b - G_b; round-off ~1e-12 of
// ~1e3 rad/s^2, asserted 1e-8), and phi_ddot = 0.
TEST(MultiArmGroundTest, SupportedRowsAreTheSimulatorsOnTheGround) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const Model model(vehicle);
  const Model::State x = GroundState();
  const Model::State x_dot = model.Derivative(x, Supported());
  MultiArmPlantState plant = MultiArmPlantState::Zero(MultiArmPlantSize(vehicle));
  MultiArmPlantInput input;
  for (int i = 0; i < 3; ++i) {
    plant(MultiArmQIndex(vehicle, DeflectionIndex(i))) = x(L::Deflection(i));
    plant(MultiArmVIndex(vehicle, DeflectionIndex(i))) = x(L::DeflectionRate(i));
    plant(MultiArmOmegaIndex(vehicle, i)) = x(L::Omega(i));
    input.thrust_scale[static_cast<size_t>(i)] = x(L::ThrustScale(i));
  }
  const MultiArmPlantState plant_dot = MultiArmSupportedDerivative(vehicle, plant, input);
  EXPECT_EQ(x_dot(L::kPitchRate), 0.0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(x_dot(L::DeflectionRate(i)), plant_dot(MultiArmVIndex(vehicle, DeflectionIndex(i))), 1e-8) << i;
    EXPECT_EQ(x_dot(L::Deflection(i)), x(L::DeflectionRate(i))) << i;
  }
}

// The support of the trirotor at rest: N = M g - F_z with F_z = sum f_i
// cos theta_i. Motors stopped: N = M g = 47.7 N, on the ground; the hover
// thrusts (27.47, 14.32, 14.32 N: F_z = 47.72 N = M g): N = 0, in the air.
TEST(MultiArmGroundTest, ContactFromTheThrustAlongBodyZ) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const EkfOptions options;
  const double g = vehicle.gravity_m_s2;
  const HoverSolution hover = SolveHover(vehicle);
  MultiArmGroundContact resting(vehicle, options), hovering(vehicle, options);
  const double stopped[3] = {0.0, 0.0, 0.0};
  const double hover_n[3] = {hover.thrust_n[0], hover.thrust_n[1], hover.thrust_n[2]};
  for (int k = 0; k < 1000; ++k) {  // 1 s at 1 kHz: fifty filter time constants from N_f = 0
    resting.Update(1000 * k, g, stopped);
    hovering.Update(1000 * k, g, hover_n);
  }
  EXPECT_TRUE(resting.supported());
  EXPECT_NEAR(resting.contact().support_force_n(), vehicle.TotalMass() * g, 1e-9);
  EXPECT_FALSE(hovering.supported());
  EXPECT_NEAR(hovering.contact().support_force_n(), 0.0, 1e-6);
  // The accelerometer's extra a_z variance (N_f / M)^2: g^2 after the rest
  // (N_f = M g), and exactly 0 for a start in the air (never supported).
  EXPECT_NEAR(resting.ReleasedSupportVarianceM2S4(), g * g, 1e-9);
  EXPECT_EQ(hovering.ReleasedSupportVarianceM2S4(), 0.0);
}

// After a time on the ground the support the contact may miss (up to
// ground_contact_on_n) widens a_z while POSE puts the body within
// ground_may_touch_m of the height the ground held it at, from
// ground_may_touch_after_s after the contact let go; before that, above
// the band, or without POSE, only the filtered support N_f does (here 0:
// released at hover thrust, N_f decayed).
TEST(MultiArmGroundTest, MayTouchBandWidensTheAccelerometerNearTheGround) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  EkfOptions options;
  options.ground_may_touch_m = 0.02;
  options.ground_may_touch_after_s = 0.3;
  const double g = vehicle.gravity_m_s2;
  const HoverSolution hover = SolveHover(vehicle);
  const double stopped[3] = {0.0, 0.0, 0.0};
  const double hover_n[3] = {hover.thrust_n[0], hover.thrust_n[1], hover.thrust_n[2]};
  MultiArmGroundContact contact(vehicle, options);
  int64_t utime = 0;
  for (int k = 0; k < 400; ++k, utime += 1000) contact.Update(utime, g, stopped);
  ASSERT_TRUE(contact.supported());
  contact.OnPose(0.10);  // the ground's height where it held the body 0.4 s (a rest) [m]
  for (int k = 0; k < 100; ++k, utime += 1000) contact.Update(utime, g, hover_n);
  ASSERT_FALSE(contact.supported());
  contact.OnPose(0.115);  // 1.5 cm up, but less than 0.3 s after the let-go: a_z at full weight
  EXPECT_FALSE(contact.contact().may_touch());
  for (int k = 0; k < 300; ++k, utime += 1000) contact.Update(utime, g, hover_n);
  ASSERT_LT(contact.contact().support_force_n(), 1e-6);
  const double bound = options.ground_contact_on_n / vehicle.TotalMass();  // [m/s^2]
  // 1.5 cm up, 0.3 s on: may touch.
  EXPECT_TRUE(contact.contact().may_touch());
  EXPECT_NEAR(contact.ReleasedSupportVarianceM2S4(), bound * bound, 1e-12);
  // ... and a touch may hold the pitch: the gyro's variance gains the predicted rate's square.
  EXPECT_NEAR(contact.HeldRateVariance(0.3), 0.09, 1e-15);
  EXPECT_EQ(contact.HeldRateVariance(std::nan("")), 0.0);
  contact.OnPose(0.125);  // 2.5 cm up: clear
  EXPECT_FALSE(contact.contact().may_touch());
  EXPECT_LT(contact.ReleasedSupportVarianceM2S4(), 1e-12);
  EXPECT_EQ(contact.HeldRateVariance(0.3), 0.0);
  // Off (0 m): never within the band.
  options.ground_may_touch_m = 0.0;
  MultiArmGroundContact off(vehicle, options);
  for (int k = 0; k < 200; ++k) off.Update(1000 * k, g, stopped);
  off.OnPose(0.10);
  for (int k = 200; k < 600; ++k) off.Update(1000 * k, g, hover_n);
  off.OnPose(0.10);
  EXPECT_FALSE(off.contact().may_touch());
  EXPECT_LT(off.ReleasedSupportVarianceM2S4(), 1e-12);
  // A start in the air never had a ground height: 0 at any pose.
  MultiArmGroundContact airborne(vehicle, EkfOptions());
  for (int k = 0; k < 200; ++k) airborne.Update(1000 * k, g, hover_n);
  airborne.OnPose(0.0);
  EXPECT_EQ(airborne.ReleasedSupportVarianceM2S4(), 0.0);
  EXPECT_EQ(airborne.HeldRateVariance(0.3), 0.0);
}

MultiArmAccuracy GroundStart(const std::string& vehicle, const std::string& scenario,
                             const std::vector<std::string>& overrides) {
  const VehicleDescription description = Vehicle(vehicle);
  return RunMultiArmAccuracy(description, ScenarioFor(scenario, overrides, description.arm_count), Config(),
                             EvalOptions());
}

void ExpectHonest(const MultiArmAccuracy& r, const std::vector<double>& max_mae_n, int64_t max_beyond_3sigma) {
  ASSERT_EQ(r.n_rotors, static_cast<int>(max_mae_n.size()));
  EXPECT_EQ(r.nonfinite, 0);
  EXPECT_GT(r.before_liftoff, 3000);  // the 3 s rest and the spool-up, not scored
  for (size_t i = 0; i < max_mae_n.size(); ++i) {
    EXPECT_LT(r.rotor[i].mae_n, max_mae_n[i]) << "rotor " << i + 1;
    EXPECT_GT(r.rotor[i].share_within_2sigma, 0.93) << "rotor " << i + 1;
    EXPECT_LT(r.rotor[i].share_within_2sigma, 0.98) << "rotor " << i + 1;
  }
  EXPECT_GT(r.valid_share, 0.99);
  EXPECT_EQ(r.false_alarms, 0);
  EXPECT_LE(r.before_liftoff_valid_beyond_3sigma, max_beyond_3sigma);
}

// Trirotor, offsets 1.5e-5 / -1.0e-5 / 0.5e-5 rad: measured MAE 0.0769 /
// 0.0507 / 0.0505 N after lift-off (2-sigma 0.959 / 0.971 / 0.970; before
// the ground phase 3.27 / 2.80 / 1.21 N, share 0.15-0.28, 17457 false
// alarms), VALID 1.000, no false alarm, none of 3627 estimates before
// lift-off VALID and beyond 3 sigma. Asserted: MAE within 15 % of the
// airborne hover (0.0788 / 0.0509 / 0.0502 N, docs/estimator.md), shares 0.93-0.98.
TEST(MultiArmGroundTest, TrirotorGaugeOffsetFromTheGround) {
  ExpectHonest(GroundStart("trirotor", "gauge_offset", {"gauge.offset_rad=[1.5e-5, -1.0e-5, 0.5e-5]"}),
               {1.15 * 0.0788, 1.15 * 0.0509, 1.15 * 0.0502}, 0);
}

// Trirotor, drift 3e-6 / 2e-6 / 1e-6 rad/s for 20 s from the lift-off:
// measured 0.0793 / 0.0504 / 0.0500 N (0.952 / 0.972 / 0.971), none of 3656
// estimates before the lift-off VALID and beyond 3 sigma. With the contact
// letting go at 2 N (ground_contact_off_n before) 12 were, all in the 12 ms
// before the lift-off (t = 4.144-4.155 s, rotor 2 low by 0.3-0.5 N: the free
// body predicted while the ground still held the body level against the
// controller's moment); at 1 N the held body is kept until the support is
// nearly gone.
TEST(MultiArmGroundTest, TrirotorGaugeDriftFromTheGround) {
  ExpectHonest(GroundStart("trirotor", "gauge_drift", {"gauge.drift_rad_s=[3.0e-6, 2.0e-6, 1.0e-6]"}),
               {1.15 * 0.0788, 1.15 * 0.0509, 1.15 * 0.0502}, 0);
}

// Trirotor, hover from the ground with a climb to 0.5 m over 2 s: measured
// 0.0783 / 0.0514 / 0.0499 N (0.955 / 0.971 / 0.971), none of 3611
// estimates before the lift-off VALID and beyond 3 sigma.
TEST(MultiArmGroundTest, TrirotorHoverClimbFromTheGround) {
  ExpectHonest(GroundStart("trirotor", "hover",
                           {"ground.enabled=true", "trajectory.kind=waypoints",
                            "trajectory.waypoints=[{start_s: 0.0, duration_s: 2.0, x_m: 0.0, z_m: 0.5}]"}),
               {1.15 * 0.0788, 1.15 * 0.0509, 1.15 * 0.0502}, 0);
}

// N = 2 through the description: measured 0.0690 / 0.0673 N (0.957 /
// 0.961), the birotor's own EKF 0.0691 / 0.0674 N (birotor-eval --scenarios
// gauge_offset --methods ekf); none of 3659 estimates before the lift-off
// VALID and beyond 3 sigma (2 without the released support's accelerometer
// variance, MultiArmGroundContact). MAE asserted within 5 % of the birotor's own.
TEST(MultiArmGroundTest, BirotorDescriptionMatchesTheBirotorsOwnEkf) {
  ExpectHonest(GroundStart("birotor", "gauge_offset", {}), {1.05 * 0.0692, 1.05 * 0.0676}, 0);
}

// One flight with the ground phase (`scenario` on `seed`): never
// MODEL_MISMATCH, VALID, every rotor's MAE below max_mae_n [N] and its
// 2-sigma share above 0.90.
void ExpectHonestNearTheGround(const VehicleDescription& description, const char* scenario, int seed,
                               double max_mae_n) {
  SCOPED_TRACE(std::string(scenario) + " seed " + std::to_string(seed));
  const MultiArmAccuracy r = RunMultiArmAccuracy(
      description,
      ScenarioFor(scenario, {"ground.enabled=true", "scenario.seed=" + std::to_string(seed)}, description.arm_count),
      Config(), EvalOptions());
  EXPECT_EQ(r.nonfinite, 0);
  EXPECT_EQ(r.mismatch_share, 0.0);
  EXPECT_GT(r.valid_share, 0.99);
  for (int i = 0; i < r.n_rotors; ++i) {
    EXPECT_LT(r.rotor[static_cast<size_t>(i)].mae_n, max_mae_n) << "rotor " << i + 1;
    EXPECT_GT(r.rotor[static_cast<size_t>(i)].share_within_2sigma, 0.90) << "rotor " << i + 1;
  }
}

// Hovering at the ground's height (hover with the ground phase: the
// setpoint z = 0 keeps the body in and out of contact below the contact's
// threshold) with the shipped may-touch band (ground_may_touch_m 0.02 m,
// from ground_may_touch_after_s 0.5 s after the let-go) and the offsets held
// from the accelerometer near the ground (MultiArmEkf's
// AccelerometerOffsetHold). Measured (seed 1): trirotor 0.1022 / 0.0671 /
// 0.0661 N, 2-sigma 0.990 / 0.967 / 0.977, VALID 1.000, MODEL_MISMATCH
// 0.000 (without the hold 0.1073 / 0.0683 / 0.0666 N, 0.965 / 0.948 /
// 0.960; without the band as well 0.1138 / 0.0626 / 0.0607 N, 0.852 / 0.923
// / 0.925, MODEL_MISMATCH 0.127); N = 2 0.1068 / 0.1082 N, 0.997 / 0.994
// (without the hold 0.0931 / 0.0969 N, 0.989 / 0.986; the birotor's own
// EKF, which holds every offset near the ground, 0.966-0.995 on seeds
// 1-10). The MAE stays above the airborne hover's: the support is unknown
// there; asserted: the sigma says so. In and out of contact the arm mode
// never gets the 0.6 s of free flight a reading needs, so the tip mass's
// prior stays in the N-arm sigma for the flight (upper bound 0.998 there).
TEST(MultiArmGroundTest, HoverAtTheGroundsHeightIsHonestWithTheBand) {
  const EstimatorConfig config = Config();
  for (const char* vehicle : {"trirotor", "birotor"}) {
    SCOPED_TRACE(vehicle);
    const VehicleDescription description = Vehicle(vehicle);
    const MultiArmAccuracy r = RunMultiArmAccuracy(
        description, ScenarioFor("hover", {"ground.enabled=true"}, description.arm_count), config, EvalOptions());
    EXPECT_EQ(r.nonfinite, 0);
    for (int i = 0; i < r.n_rotors; ++i) {
      EXPECT_LT(r.rotor[static_cast<size_t>(i)].mae_n, 0.13) << "rotor " << i + 1;
      EXPECT_GT(r.rotor[static_cast<size_t>(i)].share_within_2sigma, 0.93) << "rotor " << i + 1;
      EXPECT_LT(r.rotor[static_cast<size_t>(i)].share_within_2sigma, 0.998) << "rotor " << i + 1;
    }
    EXPECT_GT(r.valid_share, 0.99);
    EXPECT_EQ(r.mismatch_share, 0.0);
    EXPECT_EQ(r.false_alarms, 0);
  }
}

// The trirotor's worst seeds hovering at the ground's height, 5 and 6:
// near the ground a_z may carry a support that its widened variance covers
// but does not centre, and its innovations moved the gauge offsets through
// P's correlations (rotor 1 2-sigma share 0.831 / 0.870, 0.1646 / 0.1491 N).
// Held from the accelerometer there: 0.911 / 0.919, 0.1564 / 0.1537 N,
// VALID 1.000, no MODEL_MISMATCH (holding them from every input instead
// raised MODEL_MISMATCH on both seeds for 0.126 of the flight: the strain's
// window bias on arm 1 above 1).
TEST(MultiArmGroundTest, TheAccelerometerNearTheGroundDoesNotMoveTheOffsets) {
  for (const int seed : {5, 6}) ExpectHonestNearTheGround(Vehicle("trirotor"), "hover", seed, 0.16);
}

// The N = 2 description's flights whose touches the gyro's gate rejected:
// a touch holds the body's pitch (the simulator clamps it, as a landing gear
// on the ground would) while the filter's model turns it, so before the
// held rate's variance (GroundContact::HeldRateVariance) the gyro was gated
// in 22-36 % of a window and MODEL_MISMATCH held 0.252 / 0.252 / 0.142 of
// hovering at the ground's height on seeds 2 / 3 / 5 and 0.184 of gentle
// from the ground on seed 1. Measured now: never raised; MAE 0.0949 /
// 0.1177 / 0.1091 N and 0.0834 N on the worse rotor, 2-sigma 0.910-0.979.
TEST(MultiArmGroundTest, TouchesThatHoldThePitchRaiseNoMismatch) {
  const VehicleDescription description = Vehicle("birotor");
  const std::pair<const char*, int> flights[] = {{"hover", 2}, {"hover", 3}, {"hover", 5}, {"gentle", 1}};
  for (const auto& [scenario, seed] : flights) ExpectHonestNearTheGround(description, scenario, seed, 0.13);
}

// A payload at a ground start: the trirotor flown with its body 10 % heavier
// (4.4 kg) than its description, gentle from the ground. The lift-off's
// accelerometer says the model is wrong: measured MODEL_MISMATCH 0.750 of
// the scored estimates, VALID 0.250. The may-touch band starts 0.5 s after
// the contact let go for this reason: from the let-go on, its widened a_z
// let the gauge offsets take the payload during the climb through it
// (VALID 1.000, 1.57 / 0.78 / 0.79 N off, 2-sigma 0.27).
TEST(MultiArmGroundTest, PayloadAtAGroundStartIsNotHidden) {
  const EstimatorConfig config = [] {
    EstimatorConfig c = Config();
    c.vehicle = Vehicle("trirotor");
    return c;
  }();
  VehicleDescription heavier = config.vehicle;
  heavier.body_mass_kg *= 1.10;
  const Scenario gentle = ScenarioFor("gentle", {"ground.enabled=true"}, heavier.arm_count);
  const MultiArmAccuracy shipped = RunMultiArmAccuracyFlying(heavier, gentle, config, EvalOptions());
  EXPECT_GT(shipped.mismatch_share, 0.6);
  EXPECT_LT(shipped.valid_share, 0.4);
  EXPECT_EQ(shipped.nonfinite, 0);
}

// A 25 % loss on rotor 2 a second after the lift-off puts the trirotor back
// on the ground with its rotors running (thrust_loss with the ground phase,
// seed 2). The filter does not see the support (its thrust explains the
// accelerometer's weight, the ground holds the torque the gyro would show)
// and gauge 2's offset took the lost thrust: 6.6 sigma from its anchor.
// Before each gauge was judged near the ground: VALID 0.816, rotor 2 3.05 N
// off, 2-sigma share 0.105, MODEL_MISMATCH only 0.184 of the flight. Now
// (measured) MODEL_MISMATCH 0.875, VALID 0.125 (the 5 s before the loss).
TEST(MultiArmGroundTest, ALossThatPutsTheBodyBackOnTheGroundIsRaisedNotPublished) {
  const VehicleDescription trirotor = Vehicle("trirotor");
  const MultiArmAccuracy r = RunMultiArmAccuracy(
      trirotor, ScenarioFor("thrust_loss", {"ground.enabled=true", "scenario.seed=2"}, trirotor.arm_count), Config(),
      EvalOptions());
  EXPECT_EQ(r.nonfinite, 0);
  EXPECT_GT(r.mismatch_share, 0.8);
  EXPECT_LT(r.valid_share, 0.2);
}

}  // namespace
}  // namespace birotor
