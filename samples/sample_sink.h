// Where the simulator delivers its samples: one callback per channel, with
// the plain structs of samples/samples.h (N arms: multi_arm_samples.h). The service forwards them to LCM
// or a log file; tests collect them. Default callbacks ignore the sample.
#pragma once

#include "samples/multi_arm_samples.h"
#include "samples/samples.h"
#include "samples/setpoint.h"

namespace birotor {

class SampleSink {
 public:
  virtual ~SampleSink() = default;
  virtual void OnStrain(const StrainSample& /*sample*/) {}
  virtual void OnMotor(const MotorSample& /*sample*/) {}
  virtual void OnImu(const ImuSample& /*sample*/) {}
  virtual void OnPose(const PoseSample& /*sample*/) {}
  virtual void OnLoadCell(const LoadCellSample& /*sample*/) {}
  virtual void OnTruth(const TruthSample& /*sample*/) {}
  // The reference as a setpoint (only with Simulator::EmitSetpoints).
  virtual void OnSetpoint(const Setpoint& /*setpoint*/) {}
  // A vehicle with N arms (simulator/multi_arm_simulator.h); IMU and POSE
  // through OnImu and OnPose.
  virtual void OnStrainN(const MultiArmStrainSample& /*sample*/) {}
  virtual void OnMotorN(const MultiArmMotorSample& /*sample*/) {}
  virtual void OnLoadCellN(const MultiArmLoadCellSample& /*sample*/) {}
  virtual void OnTruthN(const MultiArmTruthSample& /*sample*/) {}
};

}  // namespace birotor
