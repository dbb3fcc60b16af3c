// Solve time of the MPC with N inputs (issue 38: p99 below 1 ms at 200 Hz
// with 3 inputs): a 10 s closed loop (2000 solves at 200 Hz, the default
// MpcParams) on the nonlinear plant of config/vehicles/trirotor.yaml (3
// inputs) and config/vehicles/birotor.yaml (2 inputs, for comparison), a 1 m
// lateral step at t = 0 and hover after it (controller/multi_arm_mpc_flight.h).
// Each solve is timed by the MPC itself (linearise, condense, solve, check):
// CPU time of the thread (what the solver costs) and wall time (what a
// loaded machine adds). Run build/benchmarks/multi_arm_mpc_benchmark; the
// percentiles are the counters.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "controller/multi_arm_mpc_flight.h"
#include "controller/multi_arm_mpc_model.h"
#include "numerics/percentile.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

void FlyAndTime(benchmark::State& state, const std::string& vehicle_file) {
  const VehicleDescription vehicle = LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/" + vehicle_file);
  MpcParams params;
  // Late is judged on alglib's work, so a preempted solve is timed, not
  // replaced by the fallback (which would change the flight).
  params.deadline_clock = MpcDeadlineClock::kWork;
  MultiArmMpcFlightOptions options;
  options.duration_s = 10.0;
  std::vector<double> cpu_s, wall_s;
  int fallbacks = 0, max_iterations = 0;
  for (auto _ : state) {
    const MultiArmMpcFlightResult flight = FlyMultiArmMpc(vehicle, params, options);
    cpu_s.insert(cpu_s.end(), flight.solve_cpu_s.begin(), flight.solve_cpu_s.end());
    wall_s.insert(wall_s.end(), flight.solve_wall_s.begin(), flight.solve_wall_s.end());
    fallbacks += flight.fallbacks;
    max_iterations = std::max(max_iterations, flight.max_iterations);
    benchmark::DoNotOptimize(flight.final_position_m);
  }
  state.counters["inputs"] = vehicle.arm_count;
  state.counters["solves"] = static_cast<double>(cpu_s.size());
  state.counters["cpu_p50_us"] = 1e6 * Percentile(cpu_s, 0.5);
  state.counters["cpu_p99_us"] = 1e6 * Percentile(cpu_s, 0.99);
  state.counters["cpu_max_us"] = 1e6 * Percentile(cpu_s, 1.0);
  state.counters["wall_p50_us"] = 1e6 * Percentile(wall_s, 0.5);
  state.counters["wall_p99_us"] = 1e6 * Percentile(wall_s, 0.99);
  state.counters["wall_max_us"] = 1e6 * Percentile(wall_s, 1.0);
  state.counters["max_iterations"] = max_iterations;
  state.counters["fallbacks"] = fallbacks;
}

// The linearisation alone (central differences: 2 (6 + 2N) + 1 RK4 steps of
// the N-arm body rows), the part of a solve that grows with N besides the QP.
void BM_MultiArmMpcLinearizeThreeInputs(benchmark::State& state) {
  const MultiArmMpcModel model(
      LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml"));
  const MultiArmMpcState s0 = model.HoverState();
  const MultiArmMpcContext context = model.NominalContext();
  for (auto _ : state) benchmark::DoNotOptimize(model.Linearize(s0, model.hover_speed_rad_s(), context, 0.02));
}
BENCHMARK(BM_MultiArmMpcLinearizeThreeInputs)->Unit(benchmark::kMicrosecond);

void BM_MultiArmMpcThreeInputs(benchmark::State& state) { FlyAndTime(state, "config/vehicles/trirotor.yaml"); }
void BM_MultiArmMpcTwoInputs(benchmark::State& state) { FlyAndTime(state, "config/vehicles/birotor.yaml"); }
BENCHMARK(BM_MultiArmMpcThreeInputs)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_MultiArmMpcTwoInputs)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace birotor

BENCHMARK_MAIN();
