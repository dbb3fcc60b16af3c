// Log events to the handler.
#include "sources/log_source.h"

#include <algorithm>

namespace birotor {

bool LogSource::Subscribe(const std::vector<std::string>& channels, PacketHandler* handler, std::string* /*error*/) {
  channels_ = channels;
  handler_ = handler;
  return true;
}

bool LogSource::DeliverOne() {
  if (finished_) return false;
  if (!reader_.Next(&event_)) {
    finished_ = true;
    return false;
  }
  const bool subscribed =
      channels_.empty() || std::find(channels_.begin(), channels_.end(), event_.channel) != channels_.end();
  if (subscribed && handler_ != nullptr) {
    handler_->HandlePacket(event_.channel, event_.data.data(), event_.data.size(), event_.timestamp_us);
  }
  return true;
}

}  // namespace birotor
