// birotor-replay core: log events through the daemon's estimator node.
#include "replay/replayer.h"

#include "sources/log_source.h"

namespace birotor {

template <class Service>
BasicReplayer<Service>::BasicReplayer(const EstimatorConfig& config, const ReplayOptions& options, MessageSink* sink)
    : options_(options),
      channels_(MakeChannelNames(options.prefix)),
      sink_(sink),
      service_(
          config, channels_,
          [&options] {
            EstimatorServiceOptions service_options;
            service_options.status_rate_hz = options.status_rate_hz;
            service_options.report_processing_time = false;  // deterministic output
            return service_options;
          }(),
          sink) {}

template <class Service>
int64_t BasicReplayer<Service>::StrainFaultCount() const {
  const auto& health = service_.health();
  const InputCounters& strain = health.inputs[static_cast<int>(InputChannel::kStrain)];
  return strain.gaps + strain.out_of_order + strain.duplicates + strain.rejected_invalid + strain.decode_errors +
         health.resets;
}

template <class Service>
void BasicReplayer<Service>::Process(std::string_view channel, int64_t timestamp_us, const void* data, size_t size) {
  ++stats_.events;
  if (service_.IsInputChannel(channel)) {
    ++stats_.input_packets;
    // The daemon's one way in; the arrival time is not the log's (-1: no
    // overload guard, which would compare it with the host's clock now).
    const int64_t forces_before = service_.forces_published();
    service_.HandlePacket(channel, data, size, -1);
    if (service_.forces_published() > forces_before) ++stats_.forces;
    const int64_t newest = service_.health().newest_utime;
    if (newest >= 0) {
      if (stats_.first_utime < 0) stats_.first_utime = newest;
      stats_.last_utime = newest;
    }
    const int64_t faults = StrainFaultCount();
    if (faults != strain_fault_count_) {
      strain_fault_count_ = faults;
      stats_.strain_fault_utimes.push_back(newest);
    }
    service_.PublishStatusOnVehicleClock();
  } else if (options_.copy_truth && (channel == channels_.truth || channel == channels_.truth_n)) {
    sink_->Publish(channel == channels_.truth ? channels_.truth : channels_.truth_n, timestamp_us, data, size);
    ++stats_.truth_copied;
  }
}

template class BasicReplayer<EstimatorService>;
template class BasicReplayer<MultiArmEstimatorService>;

bool ReplayLogFile(const std::string& input_path, PacketHandler* replayer, std::string* damage, std::string* error,
                   double min_usable_fraction) {
  LogSource source;
  if (!source.Open(input_path, error) || !source.Subscribe({}, replayer, error)) return false;
  while (source.DeliverOne()) {
  }
  return CheckLogUsable(source.reader(), input_path, min_usable_fraction, error, damage);
}

}  // namespace birotor
