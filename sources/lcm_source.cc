// Raw LCM subscriptions to the handler.
#include "sources/lcm_source.h"

#include <poll.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <lcm/lcm-cpp.hpp>

namespace birotor {

std::string ExactChannelRegex(const std::string& channel) {
  std::string regex;
  regex.reserve(2 * channel.size());
  for (const char c : channel) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') regex.push_back('\\');
    regex.push_back(c);
  }
  return regex;
}

LcmSource::~LcmSource() { Unsubscribe(); }

void LcmSource::Unsubscribe() {
  for (const std::unique_ptr<Route>& route : routes_) {
    if (route->subscription != nullptr) lcm_->unsubscribe(route->subscription);
  }
  routes_.clear();
}

bool LcmSource::Subscribe(const std::vector<std::string>& channels, PacketHandler* handler, std::string* error) {
  Unsubscribe();
  handler_ = handler;
  for (const std::string& channel : channels) {
    auto route = std::make_unique<Route>();
    route->source = this;
    route->channel = channel;
    route->subscription = lcm_->subscribeFunction(ExactChannelRegex(channel), &LcmSource::OnMessage, route.get());
    if (route->subscription == nullptr) {
      *error = "LCM refused a subscription to " + channel.substr(0, 80);
      Unsubscribe();
      return false;
    }
    // Keep a burst of 1 kHz samples while the loop does its periodic work.
    route->subscription->setQueueCapacity(10000);
    routes_.push_back(std::move(route));
  }
  return true;
}

void LcmSource::OnMessage(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/, Route* route) {
  if (route->source->handler_ == nullptr) return;
  route->source->handler_->HandlePacket(route->channel, buffer->data, buffer->data_size, buffer->recv_utime);
}

bool LcmSource::Wait(double timeout_s) {
  pollfd entry{};
  entry.fd = lcm_->getFileno();
  entry.events = POLLIN;
  const double timeout_ms = std::isfinite(timeout_s) ? std::min(std::max(timeout_s * 1e3, 0.0), 1e6) : 0.0;
  return ::poll(&entry, 1, static_cast<int>(std::ceil(timeout_ms))) > 0 && (entry.revents & POLLIN) != 0;
}

bool LcmSource::DeliverOne() {
  const int handled = lcm_->handleTimeout(0);
  if (handled < 0 && errno != EINTR) error_ = std::string("lcm handle failed: ") + std::strerror(errno);
  return handled > 0;
}

}  // namespace birotor
