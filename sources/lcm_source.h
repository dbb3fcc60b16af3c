// The live source on LCM's own providers other than udpm (memq:// in tests,
// file:// for lcm's log player provider): one raw subscription per channel
// on an lcm::LCM instance, delivered through lcm.handle. Never used for
// udpm:// (LCM reassembles fragments there; see sources/udpm_source.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sources/message_source.h"

namespace lcm {
class LCM;
class ReceiveBuffer;
class Subscription;
}  // namespace lcm

namespace birotor {

class LcmSource : public MessageSource {
 public:
  // lcm must outlive the source.
  explicit LcmSource(lcm::LCM* lcm) : lcm_(lcm) {}
  ~LcmSource() override;
  LcmSource(const LcmSource&) = delete;
  LcmSource& operator=(const LcmSource&) = delete;

  bool Subscribe(const std::vector<std::string>& channels, PacketHandler* handler, std::string* error) override;
  // Polls LCM's notification descriptor (readable while a message is queued).
  bool Wait(double timeout_s) override;
  bool DeliverOne() override;
  bool finished() const override { return !error_.empty(); }
  const std::string& error() const override { return error_; }
  std::string Describe() const override { return "LCM subscription"; }

 private:
  struct Route {
    LcmSource* source = nullptr;
    std::string channel;
    lcm::Subscription* subscription = nullptr;
  };
  static void OnMessage(const lcm::ReceiveBuffer* buffer, const std::string& channel, Route* route);
  void Unsubscribe();

  lcm::LCM* lcm_;
  PacketHandler* handler_ = nullptr;
  std::vector<std::unique_ptr<Route>> routes_;
  std::string error_;
};

// LCM subscribes by regular expression: channel with every character that
// is not a letter, digit or '_' escaped, so a prefix with '.' or '+' matches
// only itself.
std::string ExactChannelRegex(const std::string& channel);

}  // namespace birotor
