// The lock-step loop of evaluation/multi_arm_closed_loop.h: the product's
// N-rotor controller on the measured state (POSE, IMU) flying the trirotor
// and the birotor description of config/vehicles/ through the scenario files
// (issue 38's control targets, with the nominal map), and the same seed
// giving the same commands. Every bound is the target or the figure
// measured with birotor-eval --vehicle FILE --control (docs/controller.md) with a
// margin of at most 1.5x.
#include "evaluation/multi_arm_closed_loop.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "evaluation/estimated_efficiency_provider.h"
#include "evaluation/multi_arm_descent_floor.h"
#include "model/multi_arm_linearization.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

VehicleDescription Vehicle(const std::string& name) {
  return LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/" + name + ".yaml");
}

Scenario ScenarioFor(const std::string& name, const VehicleDescription& vehicle,
                     const std::vector<std::string>& overrides = {}) {
  return LoadScenario(std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml", overrides,
                      vehicle.arm_count);
}

// The nominal map (no efficiency estimate), the gains of ControllerConfig's
// defaults (config/controller.yaml's).
ControllerConfig Nominal() {
  ControllerConfig config;
  config.force_feedback = false;
  return config;
}

constexpr double kBandM = 0.02;  // settling band of the 1 m step (2 %) [m]

double FinalErrorM(const MultiArmClosedLoopRun& run) {
  return (run.samples.back().position_m - run.samples.back().reference_m).norm();
}

// Issue 38: the trirotor makes the 1 m lateral step at |phi| < 0.02 rad
// (measured 0.0180) and reaches the target (settled within 2 cm after 7.02 s:
// the position integral overshoots by 0.123 m and returns slowly, as the
// autopilot's; final error 10 s after the step 0.0054 m).
TEST(MultiArmClosedLoopTest, TrirotorLateralStepStaysLevel) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const MultiArmClosedLoopRun run = RunMultiArmClosedLoop(vehicle, ScenarioFor("lateral_step", vehicle), Nominal());
  const MultiArmFlightFigures f = FiguresOf(run, kBandM);
  std::printf("trirotor lateral step: max |phi| %.4f rad, settling %.2f s, overshoot %.3f m, final %.4f m\n",
              f.max_tilt_rad, f.settling_s, f.overshoot_m, FinalErrorM(run));
  EXPECT_EQ(run.mode, MultiArmControlMode::kFullyActuated);
  EXPECT_LT(f.max_tilt_rad, 0.02);
  EXPECT_LT(f.settling_s, 7.02 * 1.5);
  EXPECT_LT(f.overshoot_m, 0.123 * 1.5);
  EXPECT_LT(FinalErrorM(run), 0.0054 * 1.5);
  EXPECT_EQ(run.commands_out_of_bounds, 0);
}

// The birotor description through the same controller tilts to move: the
// issue's > 0.1 rad (measured 0.62: the tilt target's 0.5 rad bound and the
// overshoot of the inner loop; final error 0.0072 m).
TEST(MultiArmClosedLoopTest, BirotorTiltsForTheSameStep) {
  const VehicleDescription vehicle = Vehicle("birotor");
  const MultiArmClosedLoopRun run = RunMultiArmClosedLoop(vehicle, ScenarioFor("lateral_step", vehicle), Nominal());
  const MultiArmFlightFigures f = FiguresOf(run, kBandM);
  std::printf("birotor lateral step: max |phi| %.4f rad, settling %.2f s, final %.4f m\n", f.max_tilt_rad, f.settling_s,
              FinalErrorM(run));
  EXPECT_EQ(run.mode, MultiArmControlMode::kTiltToMove);
  EXPECT_GT(f.max_tilt_rad, 0.1);
  EXPECT_LT(f.max_tilt_rad, 0.62 * 1.5);
  EXPECT_LT(FinalErrorM(run), 0.0072 * 1.5);
}

// Issue 38: the trirotor's RMS on the aggressive move no worse than the
// birotor's (measured 0.0060 m against 0.0090 m).
TEST(MultiArmClosedLoopTest, TrirotorAggressiveRmsNoWorseThanTheBirotors) {
  double rms_m[2] = {0.0, 0.0};
  const char* names[2] = {"trirotor", "birotor"};
  for (int v = 0; v < 2; ++v) {
    const VehicleDescription vehicle = Vehicle(names[v]);
    const MultiArmClosedLoopRun run = RunMultiArmClosedLoop(vehicle, ScenarioFor("aggressive", vehicle), Nominal());
    rms_m[v] = FiguresOf(run, kBandM).rms_position_error_m;
    std::printf("%s aggressive: RMS %.4f m\n", names[v], rms_m[v]);
  }
  EXPECT_LE(rms_m[0], rms_m[1]);
  EXPECT_LT(rms_m[0], 0.0060 * 1.5);
  EXPECT_LT(rms_m[1], 0.0090 * 1.5);
}

// A 40 % loss on each rotor of the trirotor from 5 s of thrust_loss, nominal
// map: the baseline (measured 0.356, 0.123, 0.144 m of altitude deviation),
// every command within [0, omega_max]. With each rotor's true efficiency the
// deviation is below a fifth of it (measured 0.0067, 0.0046, 0.0063 m
// through the EfficiencyConditioner; 0.0136, 0.0071, 0.0072 m when the
// controller flew the scale itself): the 5x is within reach of an
// estimate as good as the truth.
TEST(MultiArmClosedLoopTest, TrirotorFortyPercentLossBaselineAndBound) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const double measured_m[3] = {0.356, 0.123, 0.144};
  for (int rotor = 1; rotor <= 3; ++rotor) {
    const Scenario scenario =
        ScenarioFor("thrust_loss", vehicle,
                    {"faults.thrust_steps=[{time_s: 5.0, rotor: " + std::to_string(rotor) + ", scale: 0.6}]"});
    const MultiArmClosedLoopRun nominal = RunMultiArmClosedLoop(vehicle, scenario, Nominal());
    ControllerConfig with_efficiency = Nominal();
    with_efficiency.force_feedback = true;
    TrueEfficiencyProvider truth;
    MultiArmClosedLoopOptions options;
    options.efficiency = &truth;
    const MultiArmClosedLoopRun bound = RunMultiArmClosedLoop(vehicle, scenario, with_efficiency, options);
    const double nominal_m = FiguresOf(nominal, kBandM).max_altitude_deviation_m;
    const double bound_m = FiguresOf(bound, kBandM).max_altitude_deviation_m;
    std::printf("trirotor rotor %d at 60 %%: altitude deviation %.4f m nominal, %.4f m true efficiency\n", rotor,
                nominal_m, bound_m);
    EXPECT_GT(nominal_m, measured_m[rotor - 1] / 1.5) << rotor;
    EXPECT_LT(nominal_m, measured_m[rotor - 1] * 1.5) << rotor;
    EXPECT_LT(bound_m * 5.0, nominal_m) << rotor;
    EXPECT_EQ(nominal.commands_out_of_bounds, 0) << rotor;
    EXPECT_EQ(bound.commands_out_of_bounds, 0) << rotor;
  }
}

// Issue 38: after a 40 % loss on any rotor, force feedback on the N-arm
// estimator's efficiencies (the product path: MultiArmPipeline and its EKF,
// config/estimator.yaml's defaults) keeps the altitude deviation 5x below the
// nominal map's, every command in bounds. Measured (birotor-eval --vehicle
// config/vehicles/trirotor.yaml --control), the conditioned efficiencies
// (EfficiencyConditioner, predictions not followed, the motor-lag lead):
// 0.0155 / 0.0051 / 0.0064 m against 0.3557 / 0.1231 / 0.1442 m nominal
// (23x, 24x, 23x; the scale flown itself: 0.0218 / 0.0084 / 0.0086 m; the
// estimate rings to 0.10 flagged and below 0 right after the loss,
// docs/controller.md "Vehicles with N rotors").
TEST(MultiArmClosedLoopTest, TrirotorFortyPercentLossOnTheEstimatedEfficiencies) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const double measured_m[3] = {0.0155, 0.0051, 0.0064};
  for (int rotor = 1; rotor <= 3; ++rotor) {
    const Scenario scenario =
        ScenarioFor("thrust_loss", vehicle,
                    {"faults.thrust_steps=[{time_s: 5.0, rotor: " + std::to_string(rotor) + ", scale: 0.6}]"});
    const MultiArmClosedLoopRun nominal = RunMultiArmClosedLoop(vehicle, scenario, Nominal());
    ControllerConfig with_efficiency = Nominal();
    with_efficiency.force_feedback = true;
    EstimatedEfficiencyProvider estimate(vehicle, EstimatorConfig());
    MultiArmClosedLoopOptions options;
    options.efficiency = &estimate;
    const MultiArmClosedLoopRun flown = RunMultiArmClosedLoop(vehicle, scenario, with_efficiency, options);
    const double nominal_m = FiguresOf(nominal, kBandM).max_altitude_deviation_m;
    const double flown_m = FiguresOf(flown, kBandM).max_altitude_deviation_m;
    std::printf("trirotor rotor %d at 60 %%: altitude deviation %.4f m nominal, %.4f m estimated efficiency\n", rotor,
                nominal_m, flown_m);
    EXPECT_GT(estimate.estimates(), 14000) << rotor;  // one per strain sample of the 15 s flight
    EXPECT_LT(flown_m, measured_m[rotor - 1] * 1.5) << rotor;
    EXPECT_LT(flown_m * 5.0, nominal_m) << rotor;
    EXPECT_EQ(flown.commands_out_of_bounds, 0) << rotor;
  }
}

// Mode mpc (the N-input MPC of the mpc: section, the cascade its fallback).
ControllerConfig ModelPredictive() {
  ControllerConfig config = Nominal();
  config.model_predictive = true;
  return config;
}

// Issue 38 item 3: the trirotor's lateral step in mode mpc through the
// lock-step loop at |phi| < 0.02 rad (measured 0.0111 rad), settled within
// 2 cm after 2.46 s (the cascade: 7.02 s) with 0.0012 m of overshoot (the
// cascade: 0.123 m), every solve sent (0 fallbacks of 2399 solves at 200 Hz).
TEST(MultiArmClosedLoopTest, TrirotorLateralStepInModeMpcStaysLevel) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const MultiArmClosedLoopRun run =
      RunMultiArmClosedLoop(vehicle, ScenarioFor("lateral_step", vehicle), ModelPredictive());
  const MultiArmFlightFigures f = FiguresOf(run, kBandM);
  std::printf(
      "trirotor lateral step, mode mpc: max |phi| %.4f rad, settling %.2f s, overshoot %.4f m, final %.4f m, "
      "fallbacks %lld / %lld\n",
      f.max_tilt_rad, f.settling_s, f.overshoot_m, FinalErrorM(run), static_cast<long long>(run.mpc_fallbacks),
      static_cast<long long>(run.mpc_solves));
  EXPECT_LT(f.max_tilt_rad, 0.02);
  EXPECT_LT(f.max_tilt_rad, 0.0111 * 1.5);
  EXPECT_LT(f.settling_s, 2.46 * 1.5);
  EXPECT_LT(f.overshoot_m, 0.0012 * 1.5);
  EXPECT_EQ(run.mpc_solves, 2399);
  EXPECT_EQ(run.mpc_fallbacks, 0);
  EXPECT_EQ(run.mpc_solve_cpu_s.size(), 2399u);
  EXPECT_EQ(run.commands_out_of_bounds, 0);
}

// Same scenario, same seed: the same commands, bit for bit.
TEST(MultiArmClosedLoopTest, SameSeedSameCommands) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const Scenario scenario = ScenarioFor("aggressive", vehicle, {"scenario.duration_s=2.0"});
  const MultiArmClosedLoopRun first = RunMultiArmClosedLoop(vehicle, scenario, Nominal());
  const MultiArmClosedLoopRun second = RunMultiArmClosedLoop(vehicle, scenario, Nominal());
  ASSERT_EQ(first.commands_rad_s.size(), 1000u);  // 2 s at 500 Hz
  EXPECT_EQ(first.commands_rad_s, second.commands_rad_s);
  const Scenario other = ScenarioFor("aggressive", vehicle, {"scenario.duration_s=2.0", "scenario.seed=4"});
  EXPECT_NE(RunMultiArmClosedLoop(vehicle, other, Nominal()).commands_rad_s, first.commands_rad_s);
  // Mode mpc too: its deadline is solver work in the lock-step loop.
  const MultiArmClosedLoopRun mpc = RunMultiArmClosedLoop(vehicle, scenario, ModelPredictive());
  ASSERT_EQ(mpc.commands_rad_s.size(), 400u);  // 2 s at 200 Hz
  EXPECT_EQ(mpc.commands_rad_s, RunMultiArmClosedLoop(vehicle, scenario, ModelPredictive()).commands_rad_s);
}

}  // namespace
}  // namespace birotor

namespace birotor {
namespace {

// The level-descent floor for N rotors (evaluation/multi_arm_descent_floor.h):
// a = g (1 - min_i s_i c_T omega_max^2 / f_hover,i). The birotor at s = 0.3
// and 0.2 gives docs/controller.md's 1.125 and 4.020 m/s^2 (its hover is
// m g / 2 per rotor, the deflected one within 0.01 m/s^2); the trirotor with
// rotor 1 (27.47 N) at 0.3: 9.81 (1 - 19.87 / 27.47) = 2.71 m/s^2, at 0.2:
// 5.08 m/s^2; at 0.6 hover is feasible: 0.
TEST(MultiArmDescentFloorTest, SinkAccelerationOfTheLevelDescent) {
  const VehicleDescription birotor = Vehicle("birotor");
  const VehicleDescription trirotor = Vehicle("trirotor");
  const MultiArmHover birotor_hover = SolveMultiArmHover(birotor);
  const MultiArmHover trirotor_hover = SolveMultiArmHover(trirotor);
  const std::array<double, kMaxArms> s03 = {0.3, 1.0, 1.0, 1.0, 1.0, 1.0};
  const std::array<double, kMaxArms> s02 = {0.2, 1.0, 1.0, 1.0, 1.0, 1.0};
  const std::array<double, kMaxArms> s06 = {0.6, 1.0, 1.0, 1.0, 1.0, 1.0};
  EXPECT_NEAR(MultiArmLevelSinkAccelM_S2(birotor, birotor_hover, s03), 1.125, 0.01);
  EXPECT_NEAR(MultiArmLevelSinkAccelM_S2(birotor, birotor_hover, s02), 4.020, 0.01);
  EXPECT_NEAR(MultiArmLevelSinkAccelM_S2(trirotor, trirotor_hover, s03), 2.71, 0.01);
  EXPECT_NEAR(MultiArmLevelSinkAccelM_S2(trirotor, trirotor_hover, s02), 5.08, 0.01);
  EXPECT_EQ(MultiArmLevelSinkAccelM_S2(trirotor, trirotor_hover, s06), 0.0);
}

// thrust_loss climbing to 1 m in 2 s, 8 s long, rotor `rotor` (1-based) at
// `scale` of its thrust from 5 s (birotor-eval's descentPP_rotorK cases).
// seed: the scenario's own (0) or this one.
Scenario ClimbThenLoss(const VehicleDescription& vehicle, int rotor, double scale, int seed = 0) {
  std::vector<std::string> overrides = {"trajectory.kind=waypoints",
                                        "trajectory.waypoints=[{start_s: 0.0, duration_s: 2.0, x_m: 0.0, z_m: 1.0}]",
                                        "scenario.duration_s=8.0",
                                        "faults.thrust_steps=[{time_s: 5.0, rotor: " + std::to_string(rotor) +
                                            ", scale: " + std::to_string(scale) + "}]"};
  if (seed > 0) overrides.push_back("scenario.seed=" + std::to_string(seed));
  return ScenarioFor("thrust_loss", vehicle, overrides);
}

// Force feedback on the N-arm estimator (the product path), the defaults'
// gains; spare_hover_tilt_rad as given (the default's: tilted hovers on).
MultiArmClosedLoopRun FlyOnTheEstimate(const VehicleDescription& vehicle, const Scenario& scenario,
                                       double spare_hover_tilt_rad = EfficiencyParams().spare_hover_tilt_rad,
                                       bool model_predictive = false) {
  ControllerConfig config = Nominal();
  config.force_feedback = true;
  config.model_predictive = model_predictive;
  config.efficiency.spare_hover_tilt_rad = spare_hover_tilt_rad;
  EstimatedEfficiencyProvider estimate(vehicle, EstimatorConfig());
  MultiArmClosedLoopOptions options;
  options.efficiency = &estimate;
  return RunMultiArmClosedLoop(vehicle, scenario, config, options);
}

// One flight on the estimate (FlyOnTheEstimate) and the nominal map's on the
// same scenario, in the same mode.
struct AgainstNominal {
  MultiArmClosedLoopRun run;              // on the estimate
  MultiArmFlightFigures figures;          // its figures
  MultiArmFlightFigures nominal_figures;  // the nominal map's
};

AgainstNominal FlyAgainstNominal(const VehicleDescription& vehicle, const Scenario& scenario, bool model_predictive) {
  AgainstNominal out;
  out.run = FlyOnTheEstimate(vehicle, scenario, EfficiencyParams().spare_hover_tilt_rad, model_predictive);
  ControllerConfig nominal_config = Nominal();
  nominal_config.model_predictive = model_predictive;
  out.figures = FiguresOf(out.run, kBandM);
  out.nominal_figures = FiguresOf(RunMultiArmClosedLoop(vehicle, scenario, nominal_config), kBandM);
  std::printf("  altitude deviation %.4f m (nominal map %.4f), RMS %.4f m (%.4f), max tilt %.3f rad, descents %lld\n",
              out.figures.max_altitude_deviation_m, out.nominal_figures.max_altitude_deviation_m,
              out.figures.rms_position_error_m, out.nominal_figures.rms_position_error_m, out.figures.max_tilt_rad,
              static_cast<long long>(out.run.degradation.descents));
  return out;
}

// The hover held (no descent, every command within its bounds), its altitude
// deviation and RMS within 1.5x the figures measured and below the nominal
// map's.
void ExpectHeldBetterThanNominal(const AgainstNominal& a, double deviation_m, double rms_m, const std::string& label) {
  EXPECT_EQ(a.run.degradation.descents, 0) << label;
  EXPECT_FALSE(a.run.degradation.hover_infeasible) << label;
  EXPECT_LT(a.figures.max_altitude_deviation_m, 1.5 * deviation_m) << label;
  EXPECT_LT(a.figures.rms_position_error_m, 1.5 * rms_m) << label;
  EXPECT_LT(a.figures.max_altitude_deviation_m, a.nominal_figures.max_altitude_deviation_m) << label;
  EXPECT_LT(a.figures.rms_position_error_m, a.nominal_figures.rms_position_error_m) << label;
  EXPECT_EQ(a.run.commands_out_of_bounds, 0) << label;
}

// The trirotor climbs to 1 m and loses 70 or 80 % on rotor 1 (27.5 N at
// hover) at 5 s, force feedback on the N-arm estimator (the product path):
// one descent, hover infeasible from the efficiency, one flare on the fully
// actuated budget (flare_tilt_fully_actuated_rad 0.2), peak tilt from the
// fault measured 0.139 / 0.156 rad (target <= 0.3), touchdown 2.08 / 2.97
// m/s, 0.88 / 0.93 of the level floor (target: at most 1.1 of it), below the
// nominal map's on the same flight (2.16 / 3.83 m/s: no descent, tilt 0.27
// / 1.48 rad; birotor-eval --vehicle config/vehicles/trirotor.yaml --control
// --scenarios descent70_rotor1,descent80_rotor1, the scenario's seed 4). 40
// % on rotor 1 stays feasible: no descent.
TEST(MultiArmClosedLoopTest, TrirotorDescendsLevelWhenRotorOneCannotHoldTheHover) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const double loss[3] = {0.7, 0.8, 0.4};
  const double measured_tilt_rad[3] = {0.139, 0.156, 0.029};
  for (int c = 0; c < 3; ++c) {
    const Scenario scenario = ClimbThenLoss(vehicle, 1, 1.0 - loss[c]);
    const MultiArmClosedLoopRun run = FlyOnTheEstimate(vehicle, scenario);
    const MultiArmDescent descent = MultiArmDescentOf(run, vehicle, scenario);
    std::printf("trirotor %.0f %% on rotor 1: descents %lld, peak tilt %.3f rad, touchdown %.2f m/s, floor %.2f m/s\n",
                100.0 * loss[c], static_cast<long long>(run.degradation.descents), descent.peak_tilt_rad,
                descent.touchdown_m_s, descent.floor_m_s);
    EXPECT_LT(descent.peak_tilt_rad, 1.5 * measured_tilt_rad[c]) << loss[c];
    EXPECT_EQ(run.commands_out_of_bounds, 0) << loss[c];
    if (loss[c] < 0.5) {
      EXPECT_EQ(run.degradation.descents, 0);
      EXPECT_FALSE(run.degradation.hover_infeasible);
      continue;
    }
    EXPECT_EQ(run.degradation.descents, 1) << loss[c];
    EXPECT_EQ(run.degradation.infeasible, 1) << loss[c];
    EXPECT_EQ(run.degradation.weak_rotor, 0) << loss[c];
    ASSERT_TRUE(descent.found) << loss[c];
    EXPECT_LT(descent.touchdown_m_s / descent.floor_m_s, 1.1) << loss[c];
    EXPECT_EQ(run.degradation.flares, 1) << loss[c];
    const MultiArmClosedLoopRun nominal = RunMultiArmClosedLoop(vehicle, scenario, Nominal());
    const MultiArmDescent nominal_descent = MultiArmDescentOf(nominal, vehicle, scenario);
    std::printf("  the nominal map: touchdown %.2f m/s, peak tilt %.3f rad\n", nominal_descent.touchdown_m_s,
                nominal_descent.peak_tilt_rad);
    EXPECT_LT(descent.touchdown_m_s, nominal_descent.touchdown_m_s) << loss[c];
  }
}

// The trirotor loses rotor 2 (seed 1) or rotor 3 (seed 2) altogether at 5
// s, force feedback on the N-arm estimator. FORCE reports the dead rotor's
// 0.01-0.1 N with a sigma of 0.10-0.16 N, judged against the rotors' mean
// hover thrust (a certain 0: before, judged against the force itself, mode
// mpc flew on e = 1 until 7.07 s). Without a spare rotor the dead rotor is
// held at exactly 0 N by the one tilt that balances the lateral force it
// leaves (0.40 rad, HoverSpace::LeastTiltWithoutSpare), and the cascade
// moves sideways by tilting about it (MultiArmLaw); mode mpc hands the
// vehicle to that cascade once the rotor is retired. Measured (birotor-eval
// --vehicle config/vehicles/trirotor.yaml --control --scenarios
// descent100_rotorK, the seed), altitude deviation / RMS [m]: rotor 2, the
// cascade 0.0167 / 0.0160 (the nominal map's 0.456 / 1.160), mode mpc
// 0.0127 / 0.0142 (the MPC on the nominal map 0.0181 / 0.0706); rotor 3,
// the cascade 0.0203 / 0.0400, mode mpc 0.0204 / 0.0398 (the nominal map
// lost: 25.5 / 32.7 m); before the cascade's thrust lead 0.0134 / 0.0109,
// 0.0133 / 0.0095, 0.0523 / 0.0308, 0.0581 / 0.0323. Before: the cascade descended, touchdown 0.69 /
// 0.86 m/s, and mode mpc drifted sideways, RMS 2.75 / 3.66 m.
TEST(MultiArmClosedLoopTest, TrirotorHoldsADeadRotorAtZeroNewtons) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const struct {
    int rotor;
    int seed;
    bool mpc;
    double deviation_m;
    double rms_m;
  } cases[] = {{2, 1, false, 0.0167, 0.0160},
               {2, 1, true, 0.0127, 0.0142},
               {3, 2, false, 0.0203, 0.0400},
               {3, 2, true, 0.0204, 0.0398}};
  for (const auto& c : cases) {
    std::printf("trirotor, rotor %d dead, %s:\n", c.rotor, c.mpc ? "mode mpc" : "cascade");
    const AgainstNominal a = FlyAgainstNominal(vehicle, ClimbThenLoss(vehicle, c.rotor, 0.0, c.seed), c.mpc);
    ExpectHeldBetterThanNominal(a, c.deviation_m, c.rms_m, "rotor " + std::to_string(c.rotor) + (c.mpc ? " mpc" : ""));
  }
}

// The trirotor loses 80 % on rotor 2 at 5 s: its level hover asks rotor 2
// for 14.32 N, more than its 13.25 N, but a tilted hover asks less
// (controller/hover_space.h). Force feedback on the N-arm estimate holds
// one instead of descending (before: touchdown 1.17-1.21 m/s), the one
// with rotor 2 at spare_max_share (0.11 rad: room above rotor 2), once the
// level hover has been out of reach for infeasible_s:
// - mode mpc plans about it and tilts about it to move (the tilted-hover
//   weights): altitude deviation measured 0.0048 m, RMS 0.011 m; the MPC on
//   the nominal map 0.0195 m, RMS 0.049 m (about the hover with rotor 2 at
//   1 / margin, 0.04 rad, with the level weights: 0.0073 m, RMS 0.051 m);
// - the cascade re-solves the torque and F_z on rotors 1 and 3 while
//   rotor 2 is at its bound: measured 0.0156 m, RMS 0.013 m, tilt 0.150
//   rad (along the fixed directions 0.093 m); the cascade on the nominal
//   map 0.483 m, RMS 0.380 m
// (birotor-eval --vehicle config/vehicles/trirotor.yaml --control
// --scenarios descent80_rotor2, seed 1).
TEST(MultiArmClosedLoopTest, TrirotorHoldsATiltedHoverWithRotorTwoAtTwentyPercent) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const Scenario scenario = ClimbThenLoss(vehicle, 2, 0.2, 1);
  for (bool mpc : {false, true}) {
    std::printf("trirotor, rotor 2 at 20 %%, %s:\n", mpc ? "mode mpc" : "cascade");
    const AgainstNominal a = FlyAgainstNominal(vehicle, scenario, mpc);
    // The cascade against the nominal map's 0.483 m: well below; mode mpc at half the nominal MPC's.
    ExpectHeldBetterThanNominal(a, mpc ? 0.0048 : 0.0156, mpc ? 0.011 : 0.013, mpc ? "mpc" : "cascade");
    EXPECT_LT(a.figures.max_altitude_deviation_m, (mpc ? 0.5 : 0.2) * a.nominal_figures.max_altitude_deviation_m);
  }
}

// The cascade on rotor 3 at 20 % (seed 2) and rotor 2 at 12 % (seed 1):
// the tilted hover (0.11 / 0.22 rad) holds them, measured altitude
// deviation 0.018 / 0.037 m; the nominal map's cascade falls 3.86 m and
// touches the take-off level at 1.14 m/s / holds 0.599 m low. Before the
// re-solve at a bound: 0.077 m / the level descent, touchdown 2.17 m/s.
TEST(MultiArmClosedLoopTest, TrirotorCascadeHoldsRotorThreeAtTwentyAndRotorTwoAtTwelvePercent) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const struct {
    int rotor;
    double scale;
    int seed;
    double max_deviation_m;
  } cases[] = {{3, 0.2, 2, 0.05}, {2, 0.12, 1, 0.1}};
  for (const auto& c : cases) {
    const Scenario scenario = ClimbThenLoss(vehicle, c.rotor, c.scale, c.seed);
    const MultiArmClosedLoopRun run = FlyOnTheEstimate(vehicle, scenario);
    const MultiArmClosedLoopRun nominal = RunMultiArmClosedLoop(vehicle, scenario, Nominal());
    const MultiArmFlightFigures f = FiguresOf(run, kBandM);
    const MultiArmFlightFigures n = FiguresOf(nominal, kBandM);
    std::printf(
        "trirotor, rotor %d at %.0f %%, cascade: altitude deviation %.4f m (nominal map %.3f), max tilt %.3f rad\n",
        c.rotor, 100.0 * c.scale, f.max_altitude_deviation_m, n.max_altitude_deviation_m, f.max_tilt_rad);
    EXPECT_EQ(run.degradation.descents, 0) << c.rotor;
    EXPECT_LT(f.max_altitude_deviation_m, c.max_deviation_m) << c.rotor;
    EXPECT_LT(f.max_altitude_deviation_m, 0.2 * n.max_altitude_deviation_m) << c.rotor;
    EXPECT_EQ(run.commands_out_of_bounds, 0) << c.rotor;
  }
}

// Mode mpc with rotor 2 (seed 1) or rotor 3 (seed 2) at 12 %: about the
// tilted hover (0.22 rad) the weak rotor near its bound makes F_x one way
// only; with the level tilt weights the plan could not tilt to brake and
// drifted 0.37 m sideways after the loss (RMS 0.233 / 0.430 m, where the MPC
// on the nominal map flew 0.056 m / lost the vehicle). With the
// tilted-hover weights (MpcParams tilted_hover_*) it tilts about the hover
// to move: measured altitude deviation 0.0028 / 0.0116 m, RMS 0.022 /
// 0.042 m; the MPC on the nominal map 0.0185 m, RMS 0.056 m / 18.5 m low.
TEST(MultiArmClosedLoopTest, TrirotorMpcTiltsAboutItsTiltedHoverToMove) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const struct {
    int rotor;
    int seed;
    double deviation_m;
    double rms_m;
  } cases[] = {{2, 1, 0.0028, 0.0223}, {3, 2, 0.0116, 0.0421}};
  for (const auto& c : cases) {
    std::printf("trirotor, rotor %d at 12 %%, mode mpc:\n", c.rotor);
    const AgainstNominal a = FlyAgainstNominal(vehicle, ClimbThenLoss(vehicle, c.rotor, 0.12, c.seed), true);
    ExpectHeldBetterThanNominal(a, c.deviation_m, c.rms_m, "rotor " + std::to_string(c.rotor));
    EXPECT_EQ(a.run.mpc_fallbacks, 0) << c.rotor;
  }
}

// The quadrotor loses rotors 1 and 2 at 5 s: the level hover on rotors 3
// and 4 alone (0.54 of their map) holds, but two canted rotors make F_x and
// the torque together, which the fixed directions asked for apart, and the
// cascade descended (from 5.47 s, 4.1 m below). Re-solving the torque and
// F_z on rotors 3 and 4 at a bound (F_x given up) holds it: measured
// altitude deviation 0.069 m (birotor-eval --vehicle
// config/vehicles/quadrotor.yaml --control --scenarios descent100_rotor1
// --set "faults.thrust_steps=[...rotor 1 and 2 at 0]"); the nominal map
// loses the vehicle (26 m below).
TEST(MultiArmClosedLoopTest, QuadrotorCascadeHoldsRotorsOneAndTwoDead) {
  const VehicleDescription vehicle = Vehicle("quadrotor");
  const Scenario scenario = ScenarioFor(
      "thrust_loss", vehicle,
      {"trajectory.kind=waypoints", "trajectory.waypoints=[{start_s: 0.0, duration_s: 2.0, x_m: 0.0, z_m: 1.0}]",
       "scenario.duration_s=8.0",
       "faults.thrust_steps=[{time_s: 5.0, rotor: 1, scale: 0.0}, {time_s: 5.0, "
       "rotor: 2, scale: 0.0}]"});
  const MultiArmClosedLoopRun run = FlyOnTheEstimate(vehicle, scenario);
  const MultiArmClosedLoopRun nominal = RunMultiArmClosedLoop(vehicle, scenario, Nominal());
  const double deviation_m = FiguresOf(run, kBandM).max_altitude_deviation_m;
  const double nominal_m = FiguresOf(nominal, kBandM).max_altitude_deviation_m;
  std::printf("quadrotor rotors 1 and 2 dead, cascade: descents %lld, altitude deviation %.4f m (nominal map %.2f m)\n",
              static_cast<long long>(run.degradation.descents), deviation_m, nominal_m);
  EXPECT_EQ(run.degradation.descents, 0);
  EXPECT_LT(deviation_m, 0.15);
  EXPECT_GT(nominal_m, 1.0);
  EXPECT_EQ(run.commands_out_of_bounds, 0);
}

// The quadrotor (one spare rotor) climbs to 1 m and loses 80 % on rotor 1
// at 5 s, force feedback on the N-arm estimator: rotor 1's least-norm
// hover thrust (16.8 N) is above what it makes (13.2 N), but rotors 3 and 4
// take its share (controller/hover_space.h), so it holds its height: no
// descent, altitude deviation measured 0.0755 m (birotor-eval --vehicle
// config/vehicles/quadrotor.yaml --control --scenarios descent80_rotor1;
// before the spare rotors were used: the level descent from 5.14 s). The
// nominal map on the same seed loses the vehicle (27.6 m below, tilt 2.9 rad).
TEST(MultiArmClosedLoopTest, QuadrotorHoldsAnEightyPercentLossOnItsSpareRotors) {
  const VehicleDescription vehicle = Vehicle("quadrotor");
  const Scenario scenario = ClimbThenLoss(vehicle, 1, 0.2);
  const MultiArmClosedLoopRun run = FlyOnTheEstimate(vehicle, scenario);
  const double deviation_m = FiguresOf(run, kBandM).max_altitude_deviation_m;
  std::printf("quadrotor 80 %% on rotor 1: descents %lld, altitude deviation %.4f m\n",
              static_cast<long long>(run.degradation.descents), deviation_m);
  EXPECT_EQ(run.degradation.descents, 0);
  EXPECT_FALSE(run.degradation.hover_infeasible);
  EXPECT_LT(deviation_m, 1.5 * 0.0755);
  EXPECT_EQ(run.commands_out_of_bounds, 0);
  const MultiArmClosedLoopRun nominal = RunMultiArmClosedLoop(vehicle, scenario, Nominal());
  EXPECT_GT(FiguresOf(nominal, kBandM).max_altitude_deviation_m, 1.0);
}

// Every rotor of the trirotor 3x slower than its file (tau_m x 3 on every
// arm, the scenario's vehicle ratio), hover, the cascade on the estimate:
// the thrust lead (thrust_lead_s, thrust_lead_filter_s;
// controller/motor_lag_lead.h) holds it; without the lead the cascade's attitude loop is
// lost from 2.5x (birotor-eval --vehicle config/vehicles/trirotor.yaml
// --control --scenarios hover --set vehicle.motor_time_constant_s=T, 3
// seeds: held to 4x, RMS 0.0031 m at 3x).
TEST(MultiArmClosedLoopTest, TrirotorCascadeHoldsMotorsThreeTimesSlowerThanItsFile) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const Scenario scenario = ScenarioFor("hover", vehicle, {"vehicle.motor_time_constant_s=0.105"});
  const MultiArmFlightFigures led = FiguresOf(FlyOnTheEstimate(vehicle, scenario), kBandM);
  ControllerConfig no_lead = Nominal();
  no_lead.efficiency.thrust_lead_s = 0.0;
  const MultiArmFlightFigures unled = FiguresOf(RunMultiArmClosedLoop(vehicle, scenario, no_lead), kBandM);
  std::printf("trirotor, tau_m x 3: RMS %.4f m, max tilt %.4f rad; without the lead RMS %.2f m\n",
              led.rms_position_error_m, led.max_tilt_rad, unled.rms_position_error_m);
  EXPECT_LT(led.rms_position_error_m, 1.5 * 0.0031);
  EXPECT_GT(unled.rms_position_error_m, 1.0);
}

// A dead rotor on the quadrotor (the cascade, force feedback): FORCE flags
// it below the plausibility floor, its reports there average about 0, so
// the cascade flies it as making nothing (BelowFloorEfficiency) and the
// other three hold a hover tilted against the lateral force of the rotor
// paired with the dead one (0.105 rad, the partner at 10 %;
// HoverSpace::NearestTiltedWithinShares).
// Measured (birotor-eval --vehicle config/vehicles/quadrotor.yaml --control
// --scenarios descent100_rotor3,descent100_rotor1): no descent, altitude
// deviation 0.0066 / 0.0579 m (0.0169 / 0.0479 before the cascade's thrust
// lead); the nominal map on the same seed hovers 0.38 m low (rotor 3) and
// loses the vehicle (rotor 1: 37 m below). Level
// hovers only (spare_hover_tilt_rad 0, the rule before tilted hovers): the
// hover check takes the reports (HoverFeasibility::Evidence) and the level
// descent starts at once, from 5.11 s.
TEST(MultiArmClosedLoopTest, QuadrotorHoldsADeadRotorsHoverTilted) {
  const VehicleDescription vehicle = Vehicle("quadrotor");
  const int dead_rotor[2] = {3, 1};
  const double measured_m[2] = {0.0066, 0.0579};
  for (int c = 0; c < 2; ++c) {
    const Scenario scenario = ClimbThenLoss(vehicle, dead_rotor[c], 0.0);
    const MultiArmClosedLoopRun run = FlyOnTheEstimate(vehicle, scenario);
    const double deviation_m = FiguresOf(run, kBandM).max_altitude_deviation_m;
    const MultiArmClosedLoopRun nominal = RunMultiArmClosedLoop(vehicle, scenario, Nominal());
    const double nominal_m = FiguresOf(nominal, kBandM).max_altitude_deviation_m;
    std::printf("quadrotor rotor %d dead: descents %lld, altitude deviation %.4f m (nominal map %.4f m)\n",
                dead_rotor[c], static_cast<long long>(run.degradation.descents), deviation_m, nominal_m);
    EXPECT_EQ(run.degradation.descents, 0) << dead_rotor[c];
    EXPECT_FALSE(run.degradation.hover_infeasible) << dead_rotor[c];
    EXPECT_LT(deviation_m, 1.5 * measured_m[c]) << dead_rotor[c];
    EXPECT_LT(deviation_m, 0.2 * nominal_m) << dead_rotor[c];
    EXPECT_EQ(run.commands_out_of_bounds, 0) << dead_rotor[c];
  }
  const Scenario scenario = ClimbThenLoss(vehicle, 3, 0.0);
  const MultiArmClosedLoopRun level_only = FlyOnTheEstimate(vehicle, scenario, 0.0);
  const MultiArmDescent descent = MultiArmDescentOf(level_only, vehicle, scenario);
  EXPECT_EQ(level_only.degradation.descents, 1);
  EXPECT_EQ(level_only.degradation.infeasible_by_sink, 0);
  ASSERT_TRUE(descent.found);
  EXPECT_LT(descent.start_s, 5.2);
  EXPECT_EQ(level_only.commands_out_of_bounds, 0);
}

// Mode mpc on the same dead rotors: its model needs every rotor's map, so
// it flies the reports' mean, at least spare_retire_scale (0.05), instead
// of the floor's 0.2 (which it believed the dead rotor made); with rotor 1
// dead no level hover pitches both ways (rotor 2 pinned at 0), so it plans
// about the cascade's tilted hover (MultiArmController::MpcPlansTilted)
// with the tilted-hover weights (it tilts about it to move); with rotor 3
// dead it stays level. Measured (the same command): altitude deviation
// 0.0073 / 0.0029 m, RMS position error 0.049 / 0.006 m, 0 fallbacks
// (with the level weights about the tilted hover 0.0092 m, RMS 0.123 m);
// planned level, rotor 1 drifted sideways (RMS 0.487 m, altitude 0.0085
// m); flying the floor 0.041 / 0.021 m and RMS 1.538 / 0.011 m.
TEST(MultiArmClosedLoopTest, QuadrotorMpcFliesADeadRotorAtWhatItReports) {
  const VehicleDescription vehicle = Vehicle("quadrotor");
  const int dead_rotor[2] = {1, 3};
  const double measured_m[2] = {0.0073, 0.0029};
  const double measured_rms_m[2] = {0.049, 0.006};
  for (int c = 0; c < 2; ++c) {
    const Scenario scenario = ClimbThenLoss(vehicle, dead_rotor[c], 0.0);
    const MultiArmClosedLoopRun run =
        FlyOnTheEstimate(vehicle, scenario, EfficiencyParams().spare_hover_tilt_rad, true);
    const MultiArmFlightFigures f = FiguresOf(run, kBandM);
    std::printf("quadrotor rotor %d dead, mode mpc: altitude deviation %.4f m, RMS %.3f m, fallbacks %lld\n",
                dead_rotor[c], f.max_altitude_deviation_m, f.rms_position_error_m,
                static_cast<long long>(run.mpc_fallbacks));
    EXPECT_EQ(run.degradation.descents, 0) << dead_rotor[c];
    EXPECT_EQ(run.mpc_fallbacks, 0) << dead_rotor[c];
    EXPECT_LT(f.max_altitude_deviation_m, 1.5 * measured_m[c]) << dead_rotor[c];
    EXPECT_LT(f.rms_position_error_m, 1.5 * measured_rms_m[c]) << dead_rotor[c];
    EXPECT_EQ(run.commands_out_of_bounds, 0) << dead_rotor[c];
  }
}

}  // namespace
}  // namespace birotor
