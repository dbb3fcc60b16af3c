// Solve time of the model predictive controller (issue 21: p99 under 1 ms at
// >= 100 Hz): the linearisation alone, one QP solve per alglib algorithm, and
// the whole period (Plan) over a closed-loop step, where warm starts and
// active constraints are what they are in flight. Run
// build/benchmarks/controller_benchmark; percentiles are the p50/p99/max
// counters of the Plan benchmarks.
#include <benchmark/benchmark.h>

#include <vector>

#include "controller/mpc_controller.h"
#include "controller/position_attitude_law.h"
#include "numerics/percentile.h"

namespace birotor {
namespace {

MpcState TypicalState(double hover_rad_s) {
  MpcState s = MpcState::Zero();
  s << 0.1, -0.05, 0.15, 0.4, 0.2, -0.3, hover_rad_s + 40.0, hover_rad_s - 30.0;
  return s;
}

void BM_Linearize(benchmark::State& state) {
  const MpcPredictionModel model{BirotorParams()};
  const double hover = RotorSpeedForThrust(BirotorParams(), model.hover_force_n(), 1.0);
  const MpcState s = TypicalState(hover);
  for (auto _ : state) {
    benchmark::DoNotOptimize(model.Linearize(s, s.tail<2>(), MpcModelContext(), 0.02));
  }
}
BENCHMARK(BM_Linearize)->Unit(benchmark::kMicrosecond);

// The whole period over a 4 s closed-loop flight to a 1 m x 1 m step, with the
// prediction model as the plant: solve-time percentiles as counters.
void PlanFlight(benchmark::State& state, MpcQpAlgorithm algorithm) {
  MpcParams params;
  params.algorithm = algorithm;
  params.deadline_s = 1.0;
  const MpcPredictionModel plant{BirotorParams()};
  std::vector<double> times_s;
  int64_t fallbacks = 0, max_iterations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    MpcController mpc(BirotorParams(), params);
    MpcState s = MpcState::Zero();
    s(kMpcOmega1) = s(kMpcOmega2) = mpc.rotor_speed_estimate_rad_s()(0);
    Eigen::Vector2d command = s.tail<2>();
    state.ResumeTiming();
    for (int step = 0; step < 400; ++step) {
      MpcPlanInput in;
      in.state.position_m = s.head<2>();
      in.state.phi_rad = s(kMpcPhi);
      in.state.velocity_m_s = s.segment<2>(kMpcXDot);
      in.state.phi_dot_rad_s = s(kMpcPhiDot);
      in.reference.position_m = Eigen::Vector2d(1.0, 1.0);
      in.last_command_rad_s = command;
      in.period_s = 0.01;
      const MpcPlan plan = mpc.Plan(in);
      times_s.push_back(plan.solve_time_s);
      max_iterations = std::max<int64_t>(max_iterations, plan.iterations);
      if (plan.outcome == MpcOutcome::kSolved)
        command = plan.omega_cmd_rad_s;
      else
        ++fallbacks;
      state.PauseTiming();
      s = plant.Step(s, command, MpcModelContext(), 0.01);
      mpc.Advance(command, 0.01);
      state.ResumeTiming();
    }
  }
  state.counters["p50_us"] = 1e6 * Percentile(times_s, 0.5);
  state.counters["p99_us"] = 1e6 * Percentile(times_s, 0.99);
  state.counters["max_us"] = 1e6 * Percentile(times_s, 1.0);
  state.counters["max_iterations"] = static_cast<double>(max_iterations);
  state.counters["fallbacks"] = static_cast<double>(fallbacks);
  state.counters["solves"] = static_cast<double>(times_s.size());
}
void BM_PlanDenseIpm(benchmark::State& state) { PlanFlight(state, MpcQpAlgorithm::kDenseIpm); }
void BM_PlanBleic(benchmark::State& state) { PlanFlight(state, MpcQpAlgorithm::kBleic); }
void BM_PlanDenseAul(benchmark::State& state) { PlanFlight(state, MpcQpAlgorithm::kDenseAul); }
BENCHMARK(BM_PlanDenseIpm)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_PlanBleic)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_PlanDenseAul)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace birotor

BENCHMARK_MAIN();
