// Test helper: runs a simulator scenario in-process through EstimatorPipeline
// and pairs every estimate with the truth sample of the same utime.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "estimator/estimator_pipeline.h"
#include "evaluation/eval_metrics.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "samples/sample_recorder.h"
#include "simulator/simulator.h"

namespace birotor {
namespace testing_support {

// One estimate paired with its truth.
struct PairedSample {
  int64_t utime = 0;
  double force_error_n[2] = {0, 0};  // estimate - truth [N]
  double force_std_n[2] = {0, 0};    // the estimate's one sigma [N]
  double thrust_scale[2] = {1, 1};   // estimated
  double true_thrust_scale[2] = {1, 1};
  int32_t status = 0;
  bool finite = true;
};

// The gauge offsets the pipeline reports (ESTIMATOR_STATUS) after one strain sample.
struct GaugeOffsetSample {
  int64_t utime = 0;
  double offset_rad[2] = {0, 0};
  double offset_std_rad[2] = {0, 0};
  double strain_scale[2] = {1, 1};        // learned g_i (1 when not learned)
  double strain_scale_std[2] = {0, 0};    // its published sigma
  double strain_noise_scale[2] = {1, 1};  // learned scale on each gauge's noise variance
};

struct ScenarioRun {
  std::vector<PairedSample> pairs;
  std::vector<GaugeOffsetSample> gauge_offsets;  // after every strain sample
  std::vector<ForceEstimate> forces;             // every published estimate
  std::vector<TruthSample> truth;                // every truth sample
  std::vector<FaultEvent> faults;
  PipelineHealth health;
  int64_t published = 0;
  int64_t non_finite = 0;
  int64_t liftoff_utime = -1;  // first lift-off of a scenario with a ground phase [us]
};

class PairingSink : public SampleSink {
 public:
  explicit PairingSink(EstimatorPipeline* pipeline) : pipeline_(pipeline) {}
  void OnStrain(const StrainSample& s) override {
    pipeline_->CountReceived(InputChannel::kStrain);
    ForceEstimate e;
    const bool published = pipeline_->OnStrain(s, &e);
    GaugeOffsetSample offsets;
    offsets.utime = s.utime;
    for (int i = 0; i < 2; ++i) {
      offsets.offset_rad[i] = pipeline_->health().gauge.offset_rad[i];
      offsets.offset_std_rad[i] = pipeline_->health().gauge.offset_std_rad[i];
      offsets.strain_scale[i] = pipeline_->health().gauge.strain_scale[i];
      offsets.strain_scale_std[i] = pipeline_->health().gauge.strain_scale_std[i];
      offsets.strain_noise_scale[i] = pipeline_->health().strain_noise_scale[i];
    }
    run.gauge_offsets.push_back(offsets);
    if (published) {
      last_ = e;
      run.forces.push_back(e);
      has_ = true;
      ++run.published;
      for (int i = 0; i < 2; ++i) {
        if (!std::isfinite(e.force_n[i]) || !std::isfinite(e.force_std_n[i]) || !std::isfinite(e.thrust_scale[i])) {
          ++run.non_finite;
        }
      }
    }
  }
  void OnMotor(const MotorSample& s) override {
    pipeline_->CountReceived(InputChannel::kMotor);
    pipeline_->OnMotor(s);
  }
  void OnImu(const ImuSample& s) override {
    pipeline_->CountReceived(InputChannel::kImu);
    pipeline_->OnImu(s);
  }
  void OnPose(const PoseSample& s) override {
    pipeline_->CountReceived(InputChannel::kPose);
    pipeline_->OnPose(s);
  }
  void OnTruth(const TruthSample& t) override {
    run.truth.push_back(t);
    if (!has_ || last_.utime != t.utime) return;
    PairedSample p;
    p.utime = t.utime;
    p.status = last_.status;
    for (int i = 0; i < 2; ++i) {
      p.force_error_n[i] = last_.force_n[i] - t.force_n[i];
      p.force_std_n[i] = last_.force_std_n[i];
      p.thrust_scale[i] = last_.thrust_scale[i];
      p.true_thrust_scale[i] = t.thrust_scale[i];
      p.finite = p.finite && std::isfinite(last_.force_n[i]);
    }
    run.pairs.push_back(p);
  }
  ScenarioRun run;

 private:
  EstimatorPipeline* pipeline_;
  ForceEstimate last_;
  bool has_ = false;
};

inline std::string ScenarioFile(const std::string& name) {
  return std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml";
}

// config/estimator.yaml, or the file named by $BIROTOR_ESTIMATOR_CONFIG (for tuning runs).
inline EstimatorConfig ReferenceConfig(const std::string& method = "ekf") {
  const char* file = std::getenv("BIROTOR_ESTIMATOR_CONFIG");
  EstimatorConfig config = LoadEstimatorConfig(
      file != nullptr ? std::string(file) : std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");
  config.method = method;
  return config;
}

// ReferenceConfig with the strain scales learned (EkfOptions::learn_strain_scale).
inline EstimatorConfig StrainScaleLearningConfig() {
  EstimatorConfig config = ReferenceConfig();
  config.ekf.learn_strain_scale = true;
  return config;
}

// persisted: gauge offsets the pipeline starts from (as birotor-estimator
// does from its state file); nullptr: the parameter file's.
inline ScenarioRun RunScenario(const Scenario& scenario, const EstimatorConfig& config,
                               const GaugeCalibration* persisted = nullptr) {
  EstimatorPipeline pipeline(config);
  if (persisted != nullptr) pipeline.SetGaugeOffsets(*persisted);
  PairingSink sink(&pipeline);
  Simulator simulator(scenario);
  simulator.Run(&sink);
  sink.run.faults = simulator.fault_events();
  sink.run.liftoff_utime = simulator.liftoff_utime();
  sink.run.health = pipeline.health();
  return sink.run;
}

// Mean absolute force error of rotor i [N], scored by evaluation/'s Evaluate()
// as birotor-eval scores it: estimates paired with truth by utime, from
// from_utime on, and not within exclude_s after an excluded time (sorted).
inline double ForceMae(const ScenarioRun& run, int rotor, int64_t from_utime = 0,
                       const std::vector<int64_t>& exclude_after = {}, double exclude_s = 0) {
  if (run.forces.empty()) return NAN;
  EvalOptions options;
  options.warmup_s = std::max<int64_t>(0, from_utime - run.forces.front().utime) * 1e-6;
  options.fault_exclusion_s = exclude_s;
  return Evaluate(run.forces, run.truth, exclude_after, options).mae_outside_faults_n[rotor];
}

// Share of pairs with utime >= from_utime whose rotor-i error lies inside the
// reported 2 sigma (0.95 for an honest Gaussian sigma).
inline double ShareWithin2Sigma(const ScenarioRun& run, int rotor, int64_t from_utime = 0) {
  int64_t inside = 0, count = 0;
  for (const PairedSample& p : run.pairs) {
    if (p.utime < from_utime) continue;
    ++count;
    if (std::abs(p.force_error_n[rotor]) <= 2.0 * p.force_std_n[rotor]) ++inside;
  }
  return count > 0 ? static_cast<double>(inside) / static_cast<double>(count) : NAN;
}

// Estimates with a rotor fault bit.
inline int64_t FaultFlags(const ScenarioRun& run) {
  int64_t flags = 0;
  for (const PairedSample& p : run.pairs) {
    if (p.status & (kStatusRotor1Fault | kStatusRotor2Fault)) ++flags;
  }
  return flags;
}

}  // namespace testing_support
}  // namespace birotor

namespace birotor {
namespace testing_support {

// A simulated run recorded as a time-ordered list of inputs, so that tests can
// replay it into a pipeline with faults of their own (samples/sample_recorder.h).
using InputEvent = RecordedSample;
using RecordingSink = SampleRecorder;

// Records `scenario` (a file under config/scenarios) with overrides.
inline std::vector<InputEvent> RecordScenario(const std::string& name, const std::vector<std::string>& overrides) {
  RecordingSink sink;
  Simulator simulator(LoadScenario(ScenarioFile(name), overrides));
  simulator.Run(&sink);
  return sink.events;
}

}  // namespace testing_support
}  // namespace birotor
