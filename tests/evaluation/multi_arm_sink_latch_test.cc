// The N-rotor controller's sink detection (controller/hover_feasibility.h)
// on the trirotor carrying a payload its description lacks: FORCE is
// MODEL_MISMATCH, force feedback flies the nominal map, and a sink the
// limited rotors are already slowing must not latch "hover infeasible"
// (which flew the level descent to the end). Measured with birotor-eval
// --vehicle config/vehicles/trirotor.yaml --control --scenarios thrust_loss
// --set vehicle.body_mass_kg=4.6 --set "faults.thrust_steps=[{time_s: 5.0,
// rotor: 1, scale: S}]" (the scenario's seed): S = 0.5, the cascade 0.6471 m
// on the nominal map (latched before: 2.8052 m); S = 0.45, mode mpc 0.1838 m
// (latched before: 21.6444 m). On the estimated efficiencies the cascade
// flies rotor 1's loss relative to the others (MismatchChangeRule): no worse,
// and a 40 % loss (S = 0.6) at least 2x better than the nominal map (issue
// 36's target: 0.4074 -> 0.0669 m). Mode mpc on N arms does not take that
// rule (flown, S = 0.45 latched from the sink and descended 18 m) and flies
// the nominal map under the mismatch.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "evaluation/estimated_efficiency_provider.h"
#include "evaluation/multi_arm_closed_loop.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

// Altitude deviation after the loss [m] of the trirotor, body 4.6 kg
// (+15 %), rotor 1 at scale from 5 s, in mode mpc or the cascade, on the
// nominal map or the estimated efficiencies; the sink latches counted.
double AltitudeDeviationM(double scale, bool mpc, bool force_feedback, int64_t* latched_by_sink) {
  const VehicleDescription vehicle =
      LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml");
  const Scenario scenario =
      LoadScenario(std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/thrust_loss.yaml",
                   {"vehicle.body_mass_kg=4.6",
                    "faults.thrust_steps=[{time_s: 5.0, rotor: 1, scale: " + std::to_string(scale) + "}]"},
                   vehicle.arm_count);
  ControllerConfig config;
  config.force_feedback = force_feedback;
  config.model_predictive = mpc;
  EstimatedEfficiencyProvider estimate(vehicle, EstimatorConfig());
  MultiArmClosedLoopOptions options;
  if (force_feedback) options.efficiency = &estimate;
  const MultiArmClosedLoopRun run = RunMultiArmClosedLoop(vehicle, scenario, config, options);
  *latched_by_sink = run.degradation.infeasible_by_sink;
  return FiguresOf(run, 0.02).max_altitude_deviation_m;
}

TEST(MultiArmSinkLatchTest, APayloadAndAHoldableLossFlyAsTheNominalMap) {
  for (const bool mpc : {false, true}) {
    const double scale = mpc ? 0.45 : 0.5;
    int64_t latched = 0;
    const double nominal_m = AltitudeDeviationM(scale, mpc, false, &latched);
    const double flown_m = AltitudeDeviationM(scale, mpc, true, &latched);
    std::printf("trirotor +15 %%, rotor 1 at %.2f, %s: altitude deviation %.4f m nominal, %.4f m estimated\n", scale,
                mpc ? "mpc" : "cascade", nominal_m, flown_m);
    EXPECT_LE(flown_m, 1.05 * nominal_m) << (mpc ? "mpc" : "cascade");
    EXPECT_LT(flown_m, 1.5 * (mpc ? 0.1838 : 0.6471)) << (mpc ? "mpc" : "cascade");
    EXPECT_EQ(latched, 0) << (mpc ? "mpc" : "cascade");
  }
}

TEST(MultiArmSinkLatchTest, AFortyPercentLossOnAPayloadIsFlownTwiceAsWell) {
  int64_t latched = 0;
  const double nominal_m = AltitudeDeviationM(0.6, false, false, &latched);
  const double flown_m = AltitudeDeviationM(0.6, false, true, &latched);
  std::printf("trirotor +15 %%, rotor 1 at 0.6, cascade: altitude deviation %.4f m nominal, %.4f m estimated\n",
              nominal_m, flown_m);
  EXPECT_GE(nominal_m, 2.0 * flown_m);
  EXPECT_LT(flown_m, 1.5 * 0.0669);
}

}  // namespace
}  // namespace birotor
