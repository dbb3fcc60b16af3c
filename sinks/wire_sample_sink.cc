// Simulated samples as encoded wire messages.
#include "sinks/wire_sample_sink.h"

#include "transport/counted_messages.h"
#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {

template <class Message>
void WireSampleSink::Publish(const std::string& channel, int64_t utime, const Message& message) {
  EncodeMessage(message, &buffer_);
  if (buffer_.empty()) {
    ++encode_failures_;
    return;
  }
  sink_->Publish(channel, utime, buffer_.data(), buffer_.size());
}

void WireSampleSink::OnStrain(const StrainSample& s) { Publish(channels_.strain, s.utime, ToMessage(s)); }
void WireSampleSink::OnMotor(const MotorSample& s) { Publish(channels_.motor, s.utime, ToMessage(s)); }
void WireSampleSink::OnImu(const ImuSample& s) { Publish(channels_.imu, s.utime, ToMessage(s)); }
void WireSampleSink::OnPose(const PoseSample& s) { Publish(channels_.pose, s.utime, ToMessage(s)); }
void WireSampleSink::OnLoadCell(const LoadCellSample& s) { Publish(channels_.loadcell, s.utime, ToMessage(s)); }
void WireSampleSink::OnTruth(const TruthSample& s) {
  if (publish_truth_) Publish(channels_.truth, s.utime, ToMessage(s));
}
void WireSampleSink::OnSetpoint(const Setpoint& s) { Publish(channels_.setpoint, s.utime, ToMessage(s)); }
void WireSampleSink::OnStrainN(const MultiArmStrainSample& s) { Publish(channels_.strain_n, s.utime, ToMessage(s)); }
void WireSampleSink::OnMotorN(const MultiArmMotorSample& s) { Publish(channels_.motor_n, s.utime, ToMessage(s)); }
void WireSampleSink::OnLoadCellN(const MultiArmLoadCellSample& s) {
  Publish(channels_.loadcell_n, s.utime, ToMessage(s));
}
void WireSampleSink::OnTruthN(const MultiArmTruthSample& s) {
  if (publish_truth_) Publish(channels_.truth_n, s.utime, ToMessage(s));
}
void WireSampleSink::OnVehicle(const VehicleDescription& vehicle, const std::string& publisher, int64_t utime,
                               int32_t seq) {
  vehicle_description_t message = ToMessage(vehicle, publisher);
  message.utime = utime;
  message.seq = seq;
  Publish(channels_.vehicle, utime, message);
}
void WireSampleSink::OnForce(const ForceEstimate& e) { Publish(channels_.force, e.utime, ToMessage(e)); }
void WireSampleSink::OnMotorCommand(const MotorCommand& c) { Publish(channels_.motor_command, c.utime, ToMessage(c)); }

}  // namespace birotor
