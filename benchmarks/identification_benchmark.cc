// Speed of birotor-identify's fits (issue 5 target: the 120 s `bench` log
// identified in at most 10 s), and of the flight fit on the 60 s `flight_id`
// log. The logs are simulated in-process with the project's simulator, or
// read from the lcm-logger files named by BIROTOR_BENCH_LOG and
// BIROTOR_FLIGHT_LOG when set (log reading is then outside the timing).
// Run: build/benchmarks/identification_benchmark
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "identification/identify.h"
#include "params/scenario_yaml.h"
#include "replay/identification_log_loader.h"
#include "simulator/simulator.h"

namespace birotor {
namespace {

struct CollectingSink : SampleSink {
  SensorLog* log;
  explicit CollectingSink(SensorLog* l) : log(l) {}
  void OnStrain(const StrainSample& s) override { log->strain.push_back(s); }
  void OnMotor(const MotorSample& s) override { log->motor.push_back(s); }
  void OnImu(const ImuSample& s) override { log->imu.push_back(s); }
  void OnPose(const PoseSample& s) override { log->pose.push_back(s); }
  void OnLoadCell(const LoadCellSample& s) override { log->loadcell.push_back(s); }
  void OnTruth(const TruthSample&) override {}  // never used by the fits
};

// The scenario's log from the file in env_var when set, else simulated
// (config/scenarios/<name>.yaml, full duration). *truth: the scenario's vehicle.
SensorLog ScenarioLog(const std::string& name, const char* env_var, BirotorParams* truth) {
  const Scenario scenario = LoadScenario(std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml", {});
  *truth = BirotorModelOf(scenario.vehicle);
  SensorLog log;
  if (const char* path = std::getenv(env_var); path != nullptr && *path != '\0') {
    LogLoadReport report;
    std::string error;
    if (!LoadSensorLog(path, "BIROTOR_", &log, &report, &error)) throw std::runtime_error(error);
    return log;
  }
  log.source = name;
  CollectingSink sink(&log);
  Simulator simulator(scenario);
  simulator.Run(&sink);
  return log;
}

void BM_Identify(benchmark::State& state, const std::string& name, const char* env_var, IdentificationMode mode) {
  BirotorParams truth;
  const SensorLog log = ScenarioLog(name, env_var, &truth);
  // The reference file is the base, as `birotor-identify --params` defaults to.
  const BirotorParams base;
  IdentificationResult result;
  for (auto _ : state) {
    result = Identify({log}, base, IdentificationOptions(), mode);
    benchmark::DoNotOptimize(result.params);
  }
  if (!result.ok) {
    state.SkipWithError("identification refused");
    return;
  }
  state.counters["k_error_pct"] = 100.0 * (result.params.arm_stiffness_n_m_rad / truth.arm_stiffness_n_m_rad - 1.0);
  state.counters["c_T_error_pct"] = 100.0 * (result.params.thrust_coeff_n_s2_rad2 / truth.thrust_coeff_n_s2_rad2 - 1.0);
  state.counters["tau_m_error_pct"] = 100.0 * (result.params.motor_time_constant_s / truth.motor_time_constant_s - 1.0);
}

BENCHMARK_CAPTURE(BM_Identify, bench_120s, std::string("bench"), "BIROTOR_BENCH_LOG", IdentificationMode::kBench)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_Identify, flight_id_60s, std::string("flight_id"), "BIROTOR_FLIGHT_LOG",
                  IdentificationMode::kFlight)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace
}  // namespace birotor

BENCHMARK_MAIN();
