// Flies a MultiArmPipeline on a simulator's samples in process: every
// STRAIN_N, MOTOR_N and IMU sample the N-arm simulator emits, in its order
// (the tests that read the pipeline's health after a flight).
#pragma once

#include "estimator/multi_arm_pipeline.h"
#include "samples/sample_sink.h"
#include "simulator/multi_arm_simulator.h"

namespace birotor {

inline void FlyPipeline(MultiArmSimulator* simulator, MultiArmPipeline* pipeline) {
  struct Forward : SampleSink {
    MultiArmPipeline* pipeline = nullptr;
    void OnStrainN(const MultiArmStrainSample& s) override {
      MultiArmForceEstimate estimate;
      pipeline->OnStrain(s, &estimate);
    }
    void OnMotorN(const MultiArmMotorSample& s) override { pipeline->OnMotor(s); }
    void OnImu(const ImuSample& s) override { pipeline->OnImu(s); }
  } forward;
  forward.pipeline = pipeline;
  simulator->Run(&forward);
}

}  // namespace birotor
