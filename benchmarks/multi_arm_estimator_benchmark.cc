// The N-arm EKF (estimator/multi_arm_ekf.h) per strain sample, with the MOTOR
// and IMU samples that precede it, over 10 s of `gentle` flown by the N-arm
// simulator on the birotor (N = 2) and the trirotor (N = 3) descriptions.
// The fixed-iteration runs count instructions under callgrind, as
// BM_StrainSample/ekf/iterations of estimator_benchmark.cc:
//   valgrind --tool=callgrind --toggle-collect='birotor::MultiArmEkf<*>::Add*'
//     multi_arm_estimator_benchmark --benchmark_filter='MultiArmStrainSample/.*/iterations'
// and divide the collected Ir by the strain samples (30000). The notch the
// pipeline runs before the filter: BM_MultiArmHarmonicNotchSample below.
#include <benchmark/benchmark.h>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "estimator/harmonic_notch.h"
#include "estimator/multi_arm_ekf.h"
#include "estimator/multi_arm_linear_speed.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "samples/sample_sink.h"
#include "simulator/multi_arm_simulator.h"

namespace {

using birotor::ImuSample;
using birotor::MultiArmMotorSample;
using birotor::MultiArmStrainSample;

// The recorded inputs in emission order.
struct Recording : birotor::SampleSink {
  enum Kind { kStrain, kMotor, kImu };
  struct Event {
    Kind kind;
    size_t index;
  };
  void OnStrainN(const MultiArmStrainSample& s) override { Add(kStrain, &strain, s); }
  void OnMotorN(const MultiArmMotorSample& s) override { Add(kMotor, &motor, s); }
  void OnImu(const ImuSample& s) override { Add(kImu, &imu, s); }
  template <typename T>
  void Add(Kind kind, std::vector<T>* list, const T& sample) {
    events.push_back({kind, list->size()});
    list->push_back(sample);
  }
  std::vector<Event> events;
  std::vector<MultiArmStrainSample> strain;
  std::vector<MultiArmMotorSample> motor;
  std::vector<ImuSample> imu;
};

std::string SourceFile(const std::string& relative) { return std::string(BIROTOR_SOURCE_DIR) + "/" + relative; }

const Recording& GentleRecording(const std::string& vehicle_name) {
  static std::map<std::string, Recording> recordings;
  auto found = recordings.find(vehicle_name);
  if (found != recordings.end()) return found->second;
  const birotor::VehicleDescription vehicle =
      birotor::LoadVehicleDescription(SourceFile("config/vehicles/" + vehicle_name + ".yaml"));
  birotor::MultiArmSimulator simulator(vehicle, birotor::LoadScenario(SourceFile("config/scenarios/gentle.yaml"),
                                                                      {"scenario.duration_s=10"}, vehicle.arm_count));
  Recording& recording = recordings[vehicle_name];
  simulator.Run(&recording);
  return recording;
}

// The recording's next strain sample, the MOTOR and IMU samples before it
// handed to on_motor and on_imu; replayed again, later, at its end.
template <typename OnMotor, typename OnImu>
MultiArmStrainSample NextStrain(const Recording& recording, size_t* next, int64_t* offset_us, OnMotor&& on_motor,
                                OnImu&& on_imu) {
  const int64_t span_us = recording.strain.back().utime - recording.strain.front().utime + 1000;
  while (true) {
    if (*next == recording.events.size()) {
      *next = 0;
      *offset_us += span_us;
    }
    const Recording::Event& e = recording.events[(*next)++];
    if (e.kind == Recording::kMotor) {
      MultiArmMotorSample m = recording.motor[e.index];
      m.utime += *offset_us;
      on_motor(m);
    } else if (e.kind == Recording::kImu) {
      ImuSample i = recording.imu[e.index];
      i.utime += *offset_us;
      on_imu(i);
    } else {
      MultiArmStrainSample s = recording.strain[e.index];
      s.utime += *offset_us;
      return s;
    }
  }
}

birotor::VehicleDescription VehicleNamed(const char* vehicle_name) {
  return birotor::LoadVehicleDescription(SourceFile("config/vehicles/" + std::string(vehicle_name) + ".yaml"));
}

void BM_MultiArmStrainSample(benchmark::State& state, const char* vehicle_name) {
  const Recording& recording = GentleRecording(vehicle_name);
  const birotor::VehicleDescription vehicle = VehicleNamed(vehicle_name);
  const birotor::EstimatorConfig config = birotor::LoadEstimatorConfig(SourceFile("config/estimator.yaml"));
  std::unique_ptr<birotor::MultiArmForceEstimator> filter = birotor::MakeMultiArmEkf(vehicle, config.ekf);
  size_t next = 0;
  int64_t offset_us = 0;
  birotor::MultiArmForceEstimate estimate;
  for (auto _ : state) {
    const MultiArmStrainSample s = NextStrain(
        recording, &next, &offset_us, [&](const MultiArmMotorSample& m) { filter->AddMotor(m); },
        [&](const ImuSample& i) { filter->AddImu(i); });
    filter->AddStrain(s, &estimate);
    benchmark::DoNotOptimize(estimate);
  }
  state.SetItemsProcessed(state.iterations());
}

// The rotor-harmonic rejection MultiArmPipeline adds before the filter, per
// strain sample (the N-arm BM_HarmonicNotchSample of estimator_benchmark.cc):
// the tracked rotor speeds advanced to the sample and the 2 N notches (1x,
// 2x on each arm) re-tuned and applied. Under callgrind:
//   --toggle-collect='birotor::HarmonicNotch::*' --toggle-collect='birotor::MultiArmSpeedTracker::*'
//     --benchmark_filter='MultiArmHarmonicNotchSample/.*/iterations'
void BM_MultiArmHarmonicNotchSample(benchmark::State& state, const char* vehicle_name) {
  const Recording& recording = GentleRecording(vehicle_name);
  const birotor::VehicleDescription vehicle = VehicleNamed(vehicle_name);
  const birotor::EstimatorConfig config = birotor::LoadEstimatorConfig(SourceFile("config/estimator.yaml"));
  birotor::MultiArmSpeedTracker speeds(vehicle, config.pipeline.motor_timeout_s);
  birotor::HarmonicNotchOptions options = config.harmonic_notch;
  options.bandwidth_hz = options.multi_arm_bandwidth_hz;
  birotor::HarmonicNotch notch(options, vehicle.arm_count);
  size_t next = 0;
  int64_t offset_us = 0, last_utime = 0;
  std::array<double, birotor::kMaxArms> omega_rad_s{};
  for (auto _ : state) {
    MultiArmStrainSample s = NextStrain(
        recording, &next, &offset_us, [&](const MultiArmMotorSample& m) { speeds.AddMotor(m); },
        [](const ImuSample&) {});
    speeds.Advance(s.utime);
    for (int i = 0; i < vehicle.arm_count; ++i) omega_rad_s[static_cast<size_t>(i)] = speeds.omega_rad_s(i);
    notch.Apply(static_cast<double>(s.utime - last_utime) * 1e-6, omega_rad_s, &s);
    last_utime = s.utime;
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations());
}

constexpr int kCountedSamples = 30000;
BENCHMARK_CAPTURE(BM_MultiArmStrainSample, birotor, "birotor");
BENCHMARK_CAPTURE(BM_MultiArmStrainSample, trirotor, "trirotor");
BENCHMARK_CAPTURE(BM_MultiArmStrainSample, birotor, "birotor")->Iterations(kCountedSamples);
BENCHMARK_CAPTURE(BM_MultiArmStrainSample, trirotor, "trirotor")->Iterations(kCountedSamples);
BENCHMARK_CAPTURE(BM_MultiArmHarmonicNotchSample, birotor, "birotor");
BENCHMARK_CAPTURE(BM_MultiArmHarmonicNotchSample, trirotor, "trirotor");
BENCHMARK_CAPTURE(BM_MultiArmHarmonicNotchSample, birotor, "birotor")->Iterations(kCountedSamples);
BENCHMARK_CAPTURE(BM_MultiArmHarmonicNotchSample, trirotor, "trirotor")->Iterations(kCountedSamples);

}  // namespace

BENCHMARK_MAIN();
