// A SampleSink that keeps the estimator's inputs (strain, motor, IMU) and,
// if asked, the truth, in the order the producer delivered them: a simulated
// run recorded once and replayed into a pipeline by tests and benchmarks.
#pragma once

#include <cstdint>
#include <vector>

#include "samples/sample_sink.h"
#include "samples/samples.h"

namespace birotor {

// One recorded sample; only the member named by kind is filled.
struct RecordedSample {
  enum Kind { kStrain, kMotor, kImu, kTruth } kind = kStrain;
  StrainSample strain;
  MotorSample motor;
  ImuSample imu;
  TruthSample truth;
  // The sample's stamp [us].
  int64_t utime() const {
    switch (kind) {
      case kStrain:
        return strain.utime;
      case kMotor:
        return motor.utime;
      case kImu:
        return imu.utime;
      case kTruth:
        return truth.utime;
    }
    return 0;
  }
};

class SampleRecorder : public SampleSink {
 public:
  explicit SampleRecorder(bool record_truth = true) : record_truth_(record_truth) {}
  void OnStrain(const StrainSample& s) override { Push(RecordedSample::kStrain).strain = s; }
  void OnMotor(const MotorSample& s) override { Push(RecordedSample::kMotor).motor = s; }
  void OnImu(const ImuSample& s) override { Push(RecordedSample::kImu).imu = s; }
  void OnTruth(const TruthSample& s) override {
    if (record_truth_) Push(RecordedSample::kTruth).truth = s;
  }
  std::vector<RecordedSample> events;

 private:
  RecordedSample& Push(RecordedSample::Kind kind) {
    events.emplace_back();
    events.back().kind = kind;
    return events.back();
  }
  bool record_truth_;
};

}  // namespace birotor
