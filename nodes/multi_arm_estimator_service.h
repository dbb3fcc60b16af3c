// The estimator node for a vehicle with N arms (birotor-estimator --vehicle,
// birotor-replay --vehicle): a PacketHandler for STRAIN_N, MOTOR_N, IMU and
// POSE with checked decoding (a packet that does not decode, or a counted
// message whose count is not the vehicle's, is counted as a decode error of
// its input, never dropped silently), the N-arm pipeline
// (estimator/multi_arm_pipeline.h), one FORCE_N per accepted strain sample
// and ESTIMATOR_STATUS (the per-input counters, resets and the newest
// status; its two-rotor force fields are NaN: the forces are on FORCE_N)
// with ESTIMATOR_LEARNED_N (every arm's learned strain noise).
// FORCE_N is published plain (docs/interface.md: the counted types have no
// sealed twin yet). No allocation per packet in steady state.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "birotor/estimator_learned_n_t.hpp"
#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_n_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/motor_n_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/strain_n_t.hpp"
#include "estimator/estimator_config.h"
#include "estimator/multi_arm_pipeline.h"
#include "nodes/estimator_service.h"
#include "nodes/status_message.h"
#include "nodes/strain_arrival_guard.h"
#include "nodes/vehicle_clock_schedule.h"
#include "program/logging.h"
#include "sinks/message_sink.h"
#include "sources/channel_routes.h"
#include "sources/message_source.h"
#include "transport/channels.h"
#include "transport/counted_messages.h"
#include "transport/lcm_codec.h"

namespace birotor {

class MultiArmEstimatorService : public PacketHandler {
 public:
  // config.vehicle is the description; sink must outlive the service.
  // Throws std::invalid_argument as MultiArmPipeline does.
  MultiArmEstimatorService(const EstimatorConfig& config, const ChannelNames& channels,
                           const EstimatorServiceOptions& options, MessageSink* sink);

  // STRAIN_N, MOTOR_N, IMU, POSE.
  std::vector<std::string> InputChannels() const { return routes_.Names(); }
  bool IsInputChannel(std::string_view channel) const;
  // The one way in (see EstimatorService::HandlePacket); never throws.
  void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t receive_wall_utime) override;
  // ESTIMATOR_STATUS for a reporting period of period_s (the daemon, host
  // clock), with it ESTIMATOR_LEARNED_N (same utime and seq).
  void PublishStatus(int64_t wall_utime, double period_s);
  // Replay: ESTIMATOR_STATUS each time the vehicle clock crosses a multiple
  // of 1 / status_rate_hz (wall_utime carries the vehicle time).
  void PublishStatusOnVehicleClock();

  const MultiArmPipelineHealth& health() const { return pipeline_.health(); }
  const VehicleDescription& vehicle() const { return pipeline_.vehicle(); }
  // The gauge state file: restored before the first packet, written at a
  // clean stop (nodes/multi_arm_state_persistence.h).
  void ResumeGaugeState(const MultiArmGaugeState& state) { pipeline_.ResumeGaugeState(state); }
  MultiArmGaugeState GaugeState() const { return pipeline_.GaugeState(); }
  int64_t forces_published() const { return forces_published_; }
  int32_t status_published() const { return status_seq_; }
  const ArmCountRefusals& arm_count_refusals() const { return arm_count_refusals_; }

 private:
  enum class Route : int { kStrainN, kMotorN, kImu, kPose };
  void Dispatch(Route route, const void* data, size_t size, int64_t receive_wall_utime);
  bool Decoded(InputChannel input, DecodeError error);
  template <class CountedMessage>
  bool CountMatches(const CountedMessage& message, InputChannel input, CountRefusals* refusals);
  void HandleStrain(int64_t receive_wall_utime);

  MultiArmPipeline pipeline_;
  std::string vehicle_checksum_;  // DescriptionChecksum of the description, on ESTIMATOR_STATUS
  ChannelNames channels_;
  EstimatorServiceOptions options_;
  MessageSink* sink_;
  ChannelRoutes<Route> routes_;

  strain_n_t strain_message_;
  motor_n_t motor_message_;
  imu_t imu_message_;
  pose_t pose_message_;
  force_estimate_n_t force_message_;
  estimator_status_t status_message_;
  estimator_learned_n_t learned_message_;  // sized for the vehicle at construction
  std::vector<uint8_t> buffer_;
  MultiArmStrainSample strain_sample_;
  MultiArmMotorSample motor_sample_;

  ProcessingTimeStats processing_time_;
  int32_t status_seq_ = 0;
  int64_t forces_published_ = 0;
  VehicleClockSchedule status_schedule_;  // replay: ESTIMATOR_STATUS on the vehicle clock
  ArmCountRefusals arm_count_refusals_;
  RateLimitedLog decode_warning_;
  StrainArrivalGuard arrival_;  // overload shedding and wall-clock staleness of live strain
  RateLimitedLog arm_count_warning_;
};

}  // namespace birotor
