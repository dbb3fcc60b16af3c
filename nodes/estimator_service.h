// The estimator node: a PacketHandler (sources/message_source.h) for STRAIN,
// MOTOR, IMU and POSE (and their counted twins STRAIN_N and MOTOR_N with the
// vehicle's arm count) with checked decoding that counts a malformed packet
// instead of dropping it, one FORCE per accepted strain sample and the
// ESTIMATOR_STATUS health message with its per-arm companion
// ESTIMATOR_LEARNED_N (the learned values). Its one way in is HandlePacket(channel,
// bytes, receive time): the daemon feeds it from its live source,
// birotor-replay from a log file, the closed loop of birotor-eval and the
// fuzzers from encoded messages, so all of them run the same code.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "birotor/estimator_learned_n_t.hpp"
#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_t.hpp"
#include "birotor/guard_status_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/motor_n_t.hpp"
#include "birotor/motor_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/strain_n_t.hpp"
#include "birotor/strain_t.hpp"
#include "estimator/estimator_config.h"
#include "estimator/estimator_pipeline.h"
#include "model/vehicle_description.h"
#include "nodes/input_rejection_log.h"
#include "nodes/status_message.h"
#include "nodes/strain_arrival_guard.h"
#include "nodes/vehicle_clock_schedule.h"
#include "program/logging.h"
#include "sinks/message_sink.h"
#include "sinks/signing_sink.h"
#include "sources/authenticating_handler.h"
#include "sources/channel_routes.h"
#include "sources/message_source.h"
#include "transport/channels.h"
#include "transport/counted_messages.h"
#include "transport/lcm_codec.h"
#include "transport/udpm_receiver.h"

namespace birotor {

struct EstimatorServiceOptions {
  // ESTIMATOR_STATUS rate [Hz]: wall clock in the daemon, vehicle clock in replay.
  double status_rate_hz = 5.0;
  // Overload guard: a strain packet that waited longer than this between its
  // arrival (ReceiveBuffer::recv_utime, host clock) and its processing is
  // counted as dropped_overload and not fused, so a backlog is shed instead of
  // growing [s]. Only applies to live packets (recv time known).
  double overload_max_delay_s = 0.2;
  // Measure per-sample processing time for the status message. Replay turns
  // it off (the fields are NaN) so that its output is byte-for-byte repeatable.
  bool report_processing_time = true;
  // Shortest interval between two warnings of the same kind [s].
  double warning_interval_s = 1.0;
  // Live only: when no strain packet has arrived for this long on the host
  // clock, ESTIMATOR_STATUS says INPUT_STALE (and not VALID). FORCE cannot
  // say it, since there is no strain sample to publish one for [s].
  double stale_input_wall_s = 0.1;
  // After a FORCE this daemon did not publish arrived on its FORCE channel,
  // its FORCE says STATUS_INPUT_CONFLICT (and not VALID) for this long on
  // the host clock [s].
  double foreign_force_hold_s = 1.0;
};

// The channels the node reads (its route table maps the full names).
enum class EstimatorChannel : int {
  kStrain,    // strain_t
  kMotor,     // motor_t
  kImu,       // imu_t
  kPose,      // pose_t
  kStrainN,   // strain_n_t: the STRAIN input when its count is the vehicle's
  kMotorN,    // motor_n_t: the MOTOR input likewise
  kOwnForce,  // force_estimate_t on the own FORCE channel (a second publisher?)
};

// STRAIN_N and MOTOR_N messages refused because their arm count is not the
// vehicle's (CountCheck), per input; each is also a decode error of it.
struct ArmCountRefusals {
  CountRefusals strain;
  CountRefusals motor;
  CountCheck last = CountCheck::kMatches;  // the newest refusal's reason (kMatches: none yet)
};

class EstimatorService : public PacketHandler {
 public:
  // sink must outlive the service. The pipeline is built from config (the
  // method is config.method).
  EstimatorService(const EstimatorConfig& config, const ChannelNames& channels, const EstimatorServiceOptions& options,
                   MessageSink* sink);
  ~EstimatorService();
  EstimatorService(const EstimatorService&) = delete;
  EstimatorService& operator=(const EstimatorService&) = delete;

  // The live source's UDP counters (MessageSource::udp_counters, nullptr for
  // other sources) go into ESTIMATOR_STATUS; they must outlive the service.
  void AttachUdpCounters(const UdpReceiveCounters* counters) { udp_counters_ = counters; }
  // The signing sink behind and the authenticating handler in front of this
  // node: GUARD_STATUS goes out with each ESTIMATOR_STATUS. Both must outlive
  // the service.
  void AttachAuthentication(const SigningSink* signing, const AuthenticatingHandler* handler) {
    signing_ = signing;
    authentication_ = handler;
  }

  // The channels to subscribe a source to (the route table's names): the
  // four inputs, STRAIN_N and MOTOR_N, and the node's own FORCE (to see a
  // second publisher on it).
  std::vector<std::string> InputChannels() const { return routes_.Names(); }
  // Whether channel is one of the inputs (not the own FORCE): what replay
  // feeds from a log (a log's FORCE is the recording daemon's).
  bool IsInputChannel(std::string_view channel) const;

  // PacketHandler, the one way in: a packet of a channel of the route table.
  // An input is decoded (a failure, or a counted message whose arm count is
  // not the vehicle's, counts as a decode error of its input), fed to the
  // pipeline and, for an accepted strain sample, FORCE is published. A FORCE
  // on the own channel that this node did not publish (a second estimator on
  // the prefix) flags every FORCE with STATUS_INPUT_CONFLICT, not VALID, for
  // foreign_force_hold_s. Any other channel is ignored. receive_wall_utime
  // is the host time the packet arrived [us since epoch], or -1 when unknown
  // (replay, the lock-step closed loop). Never throws.
  void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t receive_wall_utime) override;

  // Publishes ESTIMATOR_STATUS for a reporting period of period_s, with it
  // ESTIMATOR_LEARNED_N (same utime and seq) and GUARD_STATUS, and starts a
  // new period.
  void PublishStatus(int64_t wall_utime, double period_s);
  // Replay: publishes ESTIMATOR_STATUS each time the vehicle clock (newest
  // sample utime) crosses a multiple of 1/status_rate_hz; wall_utime then
  // carries the vehicle time so the output is deterministic.
  void PublishStatusOnVehicleClock();

  const PipelineHealth& health() const { return pipeline_.health(); }
  // Gauge offsets to start from (persisted state file); see EstimatorPipeline.
  void SetGaugeOffsets(const GaugeCalibration& calibration) { pipeline_.SetGaugeOffsets(calibration); }
  const EstimatorPipeline& pipeline() const { return pipeline_; }
  const ChannelNames& channels() const { return channels_; }
  int32_t status_published() const { return status_seq_; }
  int64_t forces_published() const { return forces_published_; }
  // FORCE messages on the own FORCE channel that this node did not publish.
  int64_t foreign_forces() const { return foreign_forces_; }
  const ArmCountRefusals& arm_count_refusals() const { return arm_count_refusals_; }

 private:
  // One routed packet; the input it counts under (kStrain for STRAIN_N, ...)
  // in *input, false for the own FORCE.
  bool Dispatch(EstimatorChannel channel, const void* data, size_t size, int64_t receive_wall_utime,
                InputChannel* input);
  // A decoded strain_message_: the overload guard, the pipeline, FORCE.
  void HandleStrain(int64_t receive_wall_utime);
  // A counted message's arm count against the vehicle's; a refusal is
  // counted (under input, and as its decode error) and warned about.
  template <class CountedMessage>
  bool ArmCountMatches(const CountedMessage& message, InputChannel input, CountRefusals* refusals);
  // True if the packet decoded; else it is counted as a decode error of
  // channel and warned about (rate-limited).
  bool Decoded(InputChannel channel, DecodeError error);
  // A FORCE on the own channel: ours looped back, or a foreign publisher's.
  void CheckOwnForceChannel(const void* data, size_t size);
  bool ForeignForceActive() const;
  // GUARD_STATUS, when a handler is attached.
  void PublishGuardStatus(int64_t utime, int64_t wall_utime);

  EstimatorPipeline pipeline_;
  VehicleDescription description_;  // the birotor's (2 arms), for the counted inputs
  std::string vehicle_checksum_;    // of the configured vehicle, on ESTIMATOR_STATUS
  ChannelNames channels_;
  EstimatorServiceOptions options_;
  MessageSink* sink_;
  const std::string* input_channel_names_[kNumInputChannels];
  ChannelRoutes<EstimatorChannel> routes_;

  // Decoded messages and the output buffer, reused for every packet.
  strain_t strain_message_;
  motor_t motor_message_;
  imu_t imu_message_;
  pose_t pose_message_;
  strain_n_t strain_n_message_;
  motor_n_t motor_n_message_;
  force_estimate_t force_message_;
  estimator_status_t status_message_;
  estimator_learned_n_t learned_message_;  // sized for the vehicle at construction
  std::vector<uint8_t> buffer_;

  ProcessingTimeStats processing_time_;
  int32_t status_seq_ = 0;
  int64_t forces_published_ = 0;
  VehicleClockSchedule status_schedule_;  // replay: ESTIMATOR_STATUS on the vehicle clock
  const UdpReceiveCounters* udp_counters_ = nullptr;
  const SigningSink* signing_ = nullptr;
  const AuthenticatingHandler* authentication_ = nullptr;
  guard_status_t guard_status_{};
  // Hashes of the last published FORCE payloads (FNV-1a), to tell our own
  // looped-back FORCE from another publisher's: 1 s of FORCE at 1 kHz. Each
  // comes back once; a second copy is a second publisher of the same bytes
  // (two estimators on the same inputs).
  static constexpr size_t kPublishedHashCount = 1024;
  std::array<uint64_t, kPublishedHashCount> published_hashes_{};
  std::array<bool, kPublishedHashCount> published_seen_{};
  size_t published_hash_next_ = 0;
  int64_t foreign_forces_ = 0;
  ArmCountRefusals arm_count_refusals_;
  RateLimitedLog arm_count_warning_;
  int64_t last_foreign_force_us_ = -1;  // steady clock [us]
  RateLimitedLog foreign_warning_;
  RateLimitedLog decode_warning_;
  StrainArrivalGuard arrival_;       // overload shedding and wall-clock staleness of live strain
  RateLimitedLog mismatch_warning_;  // STATUS_MODEL_MISMATCH (issue 27)
  InputRejectionLog rejection_log_;
};

}  // namespace birotor
