// The one sample-to-wire adapter: each simulated sample (samples/samples.h)
// converted to its wire message, encoded into a buffer kept between calls and
// published on its channel through a MessageSink. birotor-sim (LCM or a log),
// birotor-eval (into the replay), the simulator benchmark and the tests all
// use it, so a new channel is one edit here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/vehicle_description.h"
#include "samples/motor_command.h"
#include "samples/sample_sink.h"
#include "sinks/message_sink.h"
#include "transport/channels.h"

namespace birotor {

class WireSampleSink : public SampleSink {
 public:
  // sink must outlive the adapter. Without publish_truth, TRUTH is not
  // published (the simulator standing in for a real vehicle).
  WireSampleSink(const ChannelNames& channels, MessageSink* sink, bool publish_truth = true)
      : channels_(channels), sink_(sink), publish_truth_(publish_truth) {}

  void OnStrain(const StrainSample& sample) override;
  void OnMotor(const MotorSample& sample) override;
  void OnImu(const ImuSample& sample) override;
  void OnPose(const PoseSample& sample) override;
  void OnLoadCell(const LoadCellSample& sample) override;
  void OnTruth(const TruthSample& sample) override;
  void OnSetpoint(const Setpoint& setpoint) override;
  // A vehicle with N arms: STRAIN_N, MOTOR_N, LOADCELL_N, TRUTH_N (TRUTH_N not without
  // publish_truth), and its description on VEHICLE (seq: the caller's count).
  void OnStrainN(const MultiArmStrainSample& sample) override;
  void OnMotorN(const MultiArmMotorSample& sample) override;
  void OnLoadCellN(const MultiArmLoadCellSample& sample) override;
  void OnTruthN(const MultiArmTruthSample& sample) override;
  void OnVehicle(const VehicleDescription& vehicle, const std::string& publisher, int64_t utime, int32_t seq);
  // The outputs of an in-process estimator and controller (lock-step closed loop).
  void OnForce(const ForceEstimate& estimate);
  void OnMotorCommand(const MotorCommand& command);

  // Samples whose message could not be encoded (not published).
  int64_t encode_failures() const { return encode_failures_; }

 private:
  template <class Message>
  void Publish(const std::string& channel, int64_t utime, const Message& message);

  ChannelNames channels_;
  MessageSink* sink_;
  bool publish_truth_;
  std::vector<uint8_t> buffer_;
  int64_t encode_failures_ = 0;
};

}  // namespace birotor
