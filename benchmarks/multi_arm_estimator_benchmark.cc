// The N-arm EKF (estimator/multi_arm_ekf.h) per strain sample, with the MOTOR
// and IMU samples that precede it, over 10 s of `gentle` flown by the N-arm
// simulator on the birotor (N = 2) and the trirotor (N = 3) descriptions.
// The fixed-iteration runs count instructions under callgrind, as
// BM_StrainSample/ekf/iterations of estimator_benchmark.cc:
//   valgrind --tool=callgrind --toggle-collect='birotor::MultiArmEkf<*>::Add*'
//     multi_arm_estimator_benchmark --benchmark_filter='MultiArmStrainSample/.*/iterations'
// and divide the collected Ir by the strain samples (30000).
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "estimator/multi_arm_ekf.h"
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

void BM_MultiArmStrainSample(benchmark::State& state, const char* vehicle_name) {
  const Recording& recording = GentleRecording(vehicle_name);
  const birotor::VehicleDescription vehicle =
      birotor::LoadVehicleDescription(SourceFile("config/vehicles/" + std::string(vehicle_name) + ".yaml"));
  const birotor::EstimatorConfig config = birotor::LoadEstimatorConfig(SourceFile("config/estimator.yaml"));
  std::unique_ptr<birotor::MultiArmForceEstimator> filter = birotor::MakeMultiArmEkf(vehicle, config.ekf);
  size_t next = 0;
  int64_t offset_us = 0;  // the recording replayed again, later
  const int64_t span_us = recording.strain.back().utime - recording.strain.front().utime + 1000;
  birotor::MultiArmForceEstimate estimate;
  for (auto _ : state) {
    while (true) {
      if (next == recording.events.size()) {
        next = 0;
        offset_us += span_us;
      }
      const Recording::Event& e = recording.events[next++];
      if (e.kind == Recording::kMotor) {
        MultiArmMotorSample m = recording.motor[e.index];
        m.utime += offset_us;
        filter->AddMotor(m);
      } else if (e.kind == Recording::kImu) {
        ImuSample i = recording.imu[e.index];
        i.utime += offset_us;
        filter->AddImu(i);
      } else {
        MultiArmStrainSample s = recording.strain[e.index];
        s.utime += offset_us;
        filter->AddStrain(s, &estimate);
        break;
      }
    }
    benchmark::DoNotOptimize(estimate);
  }
  state.SetItemsProcessed(state.iterations());
}

constexpr int kCountedSamples = 30000;
BENCHMARK_CAPTURE(BM_MultiArmStrainSample, birotor, "birotor");
BENCHMARK_CAPTURE(BM_MultiArmStrainSample, trirotor, "trirotor");
BENCHMARK_CAPTURE(BM_MultiArmStrainSample, birotor, "birotor")->Iterations(kCountedSamples);
BENCHMARK_CAPTURE(BM_MultiArmStrainSample, trirotor, "trirotor")->Iterations(kCountedSamples);

}  // namespace

BENCHMARK_MAIN();
