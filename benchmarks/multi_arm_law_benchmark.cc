// Cost of one period of the N-rotor cascade (controller/multi_arm_law.h,
// MultiArmLaw::Update: the hover base, the wrench, the allocation) on the
// quadrotor of config/vehicles/quadrotor.yaml, whose base searches its
// hovers (controller/hover_space.h) when a rotor is weak: all healthy (the
// least-norm hover fits at once: 1 nearest-hover solve), rotor 1 dead (no
// level hover within the shares: the tilted search finds one at 0.095 rad
// after 39 solves), rotors 1 and 3 dead (no hover at all: every search runs
// its whole tilt grid, 322 solves; rotors 3 and 4 alone hold a level hover,
// so 1 and 2 dead is a single solve). And the descent's flare for N rotors
// (controller/multi_arm_flare.h: the exact vertex search of its linear
// programme) on the trirotor and the quadrotor, rotor 1 at 30 %. Run
// build/benchmarks/multi_arm_law_benchmark; the time is per period.
#include <benchmark/benchmark.h>

#include <string>

#include "controller/multi_arm_flare.h"
#include "controller/multi_arm_law.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

// Rotors dead_a and dead_b (0-based) make nothing, the others nominal.
void PeriodWith(benchmark::State& state, int dead_a, int dead_b) {
  const VehicleDescription vehicle =
      LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/quadrotor.yaml");
  MultiArmLaw law(vehicle, ControllerParams(), SolveMultiArmHover(vehicle), EfficiencyParams());
  RotorEfficiencies efficiency = NominalEfficiencies();
  if (dead_a >= 0) efficiency[static_cast<size_t>(dead_a)] = 0.0;
  if (dead_b >= 0) efficiency[static_cast<size_t>(dead_b)] = 0.0;
  BodyState body;
  body.position_m = Eigen::Vector2d(0.02, -0.01);
  ReferencePoint reference;
  for (auto _ : state) {
    const MultiArmRotorCommand command = law.Update(body, reference, efficiency);
    benchmark::DoNotOptimize(command.omega_cmd_rad_s);
  }
  state.counters["base_tilt_rad"] = law.base_tilt_rad();
}

void BM_QuadrotorPeriodHealthy(benchmark::State& state) { PeriodWith(state, -1, -1); }
void BM_QuadrotorPeriodRotor1Dead(benchmark::State& state) { PeriodWith(state, 0, -1); }
void BM_QuadrotorPeriodNoHover(benchmark::State& state) { PeriodWith(state, 0, 2); }
BENCHMARK(BM_QuadrotorPeriodHealthy)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_QuadrotorPeriodRotor1Dead)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_QuadrotorPeriodNoHover)->Unit(benchmark::kMicrosecond);

// One flare solve on the vehicle, rotor 1 at 30 %, 0.2 m up, sinking at 2 m/s.
void FlareOn(benchmark::State& state, const char* name) {
  const VehicleDescription vehicle =
      LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/" + name + ".yaml");
  MultiArmFlareLimits limits = FlareGeometryOf(vehicle, 0.08);
  for (int i = 0; i < vehicle.arm_count; ++i) {
    const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
    limits.max_force_n[i] =
        (i == 0 ? 0.3 : 1.0) * arm.thrust_coeff_n_s2_rad2 * vehicle.omega_max_rad_s * vehicle.omega_max_rad_s;
  }
  FlareState flare;
  flare.height_m = 0.2;
  flare.sink_rate_m_s = 2.0;
  for (auto _ : state) {
    const MultiArmFlareForces forces = MultiArmFlareForcesFor(flare, limits);
    benchmark::DoNotOptimize(forces.force_n);
  }
}
void BM_TrirotorFlare(benchmark::State& state) { FlareOn(state, "trirotor"); }
void BM_QuadrotorFlare(benchmark::State& state) { FlareOn(state, "quadrotor"); }
BENCHMARK(BM_TrirotorFlare)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_QuadrotorFlare)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace birotor

BENCHMARK_MAIN();
