// Timing of the force estimators (issue 4 speed targets): one strain sample
// (predict + update) per method, and the whole EstimatorPipeline over a
// simulated 10 s `gentle` run (replay speed, as a real-time factor).
// Median per sample:
//   estimator_benchmark --benchmark_repetitions=10 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "estimator/estimator_pipeline.h"
#include "estimator/harmonic_notch.h"
#include "estimator/motor_speed_tracker.h"
#include "params/scenario_yaml.h"
#include "samples/rotor_count.h"
#include "samples/sample_recorder.h"
#include "simulator/simulator.h"

namespace birotor {
namespace {

using Event = RecordedSample;

// The reference `gentle` scenario cut to duration_s, recorded once.
const std::vector<Event>& GentleEvents(double duration_s) {
  static std::vector<Event> events;
  static double recorded_s = -1;
  if (recorded_s != duration_s) {
    SampleRecorder recorder(/*record_truth=*/false);
    Simulator simulator(LoadScenario(std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/gentle.yaml",
                                     {"scenario.duration_s=" + std::to_string(duration_s), "sensors.pose.enabled=false",
                                      "sensors.truth.enabled=false"}));
    simulator.Run(&recorder);
    events = std::move(recorder.events);
    recorded_s = duration_s;
  }
  return events;
}

// Walks the recording to its next strain sample, handing the motor and IMU
// samples before it to on_motor / on_imu; the recording loops with utime
// shifted by its length so that time always advances.
template <class OnMotor, class OnImu>
StrainSample NextStrain(const std::vector<Event>& events, size_t* index, int64_t* offset_us, OnMotor on_motor,
                        OnImu on_imu) {
  const int64_t period_us = 10000000;
  while (true) {
    if (*index == events.size()) {
      *index = 0;
      *offset_us += period_us;
    }
    const Event& e = events[(*index)++];
    if (e.kind == Event::kMotor) {
      MotorSample m = e.motor;
      m.utime += *offset_us;
      on_motor(m);
    } else if (e.kind == Event::kImu) {
      ImuSample i = e.imu;
      i.utime += *offset_us;
      on_imu(i);
    } else if (e.kind == Event::kStrain) {
      StrainSample s = e.strain;
      s.utime += *offset_us;
      return s;
    }
  }
}

// One strain sample through one method (with the motor and IMU samples that
// precede it). The EKF also without its accelerometer fusion and without its
// gauge offset states, to show what each costs, and with the slow vehicle
// parameters learned (issue 27: the strain scales; and the body mass).
void BM_StrainSample(benchmark::State& state, const char* method, bool accelerometer = true, bool offsets = true,
                     bool learn_strain_scale = false, bool learn_body_mass = false) {
  EstimatorConfig config;
  config.method = method;
  config.ekf.use_accelerometer = accelerometer;
  config.ekf.estimate_gauge_offsets = offsets;
  config.ekf.learn_strain_scale = learn_strain_scale;
  config.ekf.learn_body_mass = learn_body_mass;
  std::unique_ptr<ForceEstimator> estimator = MakeForceEstimator(config);
  const std::vector<Event>& events = GentleEvents(10.0);
  size_t index = 0;
  int64_t offset_us = 0;
  ForceEstimate estimate;
  StrainStepInfo info;
  FusionReports reports;  // as the pipeline keeps them: one buffer, cleared per call
  for (auto _ : state) {
    const StrainSample s = NextStrain(
        events, &index, &offset_us,
        [&](const MotorSample& m) {
          reports.clear();
          estimator->AddMotor(m, &reports);
        },
        [&](const ImuSample& i) {
          reports.clear();
          estimator->AddImu(i, &reports);
        });
    reports.clear();
    estimator->AddStrain(s, &estimate, &info, &reports);
    benchmark::DoNotOptimize(estimate);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_CAPTURE(BM_StrainSample, ekf, "ekf");
BENCHMARK_CAPTURE(BM_StrainSample, ekf_without_accelerometer, "ekf", false);
BENCHMARK_CAPTURE(BM_StrainSample, ekf_without_accelerometer_and_offsets, "ekf", false, false);
BENCHMARK_CAPTURE(BM_StrainSample, ekf_learning_strain_scale, "ekf", true, true, true);
BENCHMARK_CAPTURE(BM_StrainSample, ekf_learning_strain_scale_and_mass, "ekf", true, true, true, true);
// The same three EKF runs over a fixed 30000 samples (3 passes of the
// recording), for counting instructions per sample under callgrind (the
// cost of a sample depends on the flight phase; a timed run's count varies):
//   valgrind --tool=callgrind --toggle-collect='birotor::EkfForceEstimator::DoAdd*'
//     estimator_benchmark --benchmark_filter='StrainSample/ekf.*/iterations'
// and divide the collected Ir by the SetFilterFacts calls (docs/mismatch.md).
constexpr int kCountedSamples = 30000;
BENCHMARK_CAPTURE(BM_StrainSample, ekf, "ekf")->Iterations(kCountedSamples);
BENCHMARK_CAPTURE(BM_StrainSample, ekf_learning_strain_scale, "ekf", true, true, true)->Iterations(kCountedSamples);
BENCHMARK_CAPTURE(BM_StrainSample, ekf_learning_strain_scale_and_mass, "ekf", true, true, true, true)
    ->Iterations(kCountedSamples);
BENCHMARK_CAPTURE(BM_StrainSample, inversion, "inversion");
BENCHMARK_CAPTURE(BM_StrainSample, motor_map, "motor_map");
BENCHMARK_CAPTURE(BM_StrainSample, linear_kf, "linear_kf");
BENCHMARK_CAPTURE(BM_StrainSample, luenberger, "luenberger");

// The rotor-harmonic rejection the pipeline adds before the method, per
// strain sample: the tracked rotor speeds advanced to the sample and the four
// notches (1x, 2x on each arm) re-tuned and applied.
void BM_HarmonicNotchSample(benchmark::State& state) {
  const EstimatorConfig config;
  MotorSpeedTracker speeds(BirotorModelOf(config.vehicle), config.pipeline.motor_timeout_s);
  HarmonicNotch notch(config.harmonic_notch);
  const std::vector<Event>& events = GentleEvents(10.0);
  size_t index = 0;
  int64_t offset_us = 0, last_utime = 0;
  for (auto _ : state) {
    StrainSample s = NextStrain(
        events, &index, &offset_us, [&](const MotorSample& m) { speeds.AddMotor(m); }, [](const ImuSample&) {});
    speeds.Advance(s.utime);
    const double omega_rad_s[birotor::kBirotorRotors] = {speeds.omega_rad_s(0), speeds.omega_rad_s(1)};
    notch.Apply((s.utime - last_utime) * 1e-6, omega_rad_s, &s);
    last_utime = s.utime;
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HarmonicNotchSample);

// The whole pipeline (validation, counters, EKF) over 10 s of `gentle`:
// real_time_factor = simulated seconds per wall-clock second. shipped: the
// defaults (the gauge noise and the tip mass learned); with
// every_learning_state: the strain scales and the body mass learned too
// (each off by default), for the cost of the learning estimator (issue 36):
//   valgrind --tool=callgrind --toggle-collect='birotor::EstimatorPipeline::OnStrain*'
//     estimator_benchmark --benchmark_filter='PipelineGentle10s/.*/iterations'
// divided by the strain samples (10 000 per iteration).
void BM_PipelineGentle10s(benchmark::State& state, bool every_learning_state) {
  const std::vector<Event>& events = GentleEvents(10.0);
  EstimatorConfig config;
  if (every_learning_state) {
    config.ekf.learn_strain_scale = true;
    config.ekf.learn_body_mass = true;
    config.model_consistency.arm_mode_learn_tip_mass = true;
  }
  int64_t strain_samples = 0;
  for (auto _ : state) {
    EstimatorPipeline pipeline(config);
    ForceEstimate estimate;
    for (const Event& e : events) {
      switch (e.kind) {
        case Event::kMotor:
          pipeline.OnMotor(e.motor);
          break;
        case Event::kImu:
          pipeline.OnImu(e.imu);
          break;
        case Event::kStrain:
          pipeline.OnStrain(e.strain, &estimate);
          ++strain_samples;
          break;
        case Event::kTruth:  // not recorded here
          break;
      }
    }
    benchmark::DoNotOptimize(estimate);
  }
  state.SetItemsProcessed(strain_samples);
  state.counters["real_time_factor"] = benchmark::Counter(10.0 * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK_CAPTURE(BM_PipelineGentle10s, shipped, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PipelineGentle10s, every_learning_state, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PipelineGentle10s, shipped, false)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_PipelineGentle10s, every_learning_state, true)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace birotor

BENCHMARK_MAIN();
