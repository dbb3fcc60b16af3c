// Speed of the simulator (issue 3 target: 60 s of `gentle` written offline in
// at most 0.6 s, i.e. 100x real time). Cases: the engine alone, and the engine
// writing every channel into an LCM log as `birotor-sim --output` does.
// Run: build/benchmarks/simulator_benchmark
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "params/scenario_yaml.h"
#include "simulator/simulator.h"
#include "sinks/message_sink.h"
#include "sinks/wire_sample_sink.h"
#include "transport/channels.h"
#include "transport/log_io.h"

namespace birotor {
namespace {

std::string ScenarioFile(const std::string& name) {
  return std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml";
}

// 60 s of the named scenario (the figure is for gentle).
Scenario SixtySeconds(const std::string& name) { return LoadScenario(ScenarioFile(name), {"scenario.duration_s=60"}); }

// Engine only: samples are produced and dropped by a no-op sink.
void BM_Simulate60s(benchmark::State& state, const std::string& name) {
  const Scenario scenario = SixtySeconds(name);
  for (auto _ : state) {
    Simulator sim(scenario);
    SampleSink sink;
    sim.Run(&sink);
    benchmark::DoNotOptimize(sim.state());
  }
  state.counters["realtime_factor"] = benchmark::Counter(60.0 * state.iterations(), benchmark::Counter::kIsRate);
}

// Engine plus the LCM log, as birotor-sim --output does.
void BM_WriteLog60s(benchmark::State& state, const std::string& name) {
  const Scenario scenario = SixtySeconds(name);
  const std::string path = "/tmp/simulator_benchmark_" + std::to_string(::getpid()) + ".lcm";
  int64_t events = 0;
  for (auto _ : state) {
    Simulator sim(scenario);
    LogWriter writer;
    std::string error;
    if (!writer.Open(path, &error)) {
      state.SkipWithError(error.c_str());
      break;
    }
    LogSink log_sink(&writer);
    WireSampleSink sink(MakeChannelNames(), &log_sink);
    sim.Run(&sink);
    writer.Close();
    events = writer.events_written();
  }
  std::remove(path.c_str());
  state.counters["events"] = static_cast<double>(events);
  state.counters["realtime_factor"] = benchmark::Counter(60.0 * state.iterations(), benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(BM_Simulate60s, gentle, std::string("gentle"))->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_WriteLog60s, gentle, std::string("gentle"))->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_WriteLog60s, bench, std::string("bench"))->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace birotor

BENCHMARK_MAIN();
