// The controller fuzzers' sink: every MOTOR_COMMAND published must decode,
// be finite and lie within [0, omega_max]; anything else aborts (a finding).
#pragma once

#include <cmath>
#include <cstdlib>
#include <string>
#include <utility>

#include "birotor/motor_command_t.hpp"
#include "sinks/message_sink.h"
#include "transport/lcm_codec.h"

namespace birotor::fuzz {

class MotorCommandCheck : public MessageSink {
 public:
  MotorCommandCheck(std::string channel, double omega_max) : channel_(std::move(channel)), omega_max_(omega_max) {}
  void Publish(const std::string& channel, int64_t, const void* data, size_t size) override {
    if (channel != channel_) return;
    motor_command_t command;
    if (DecodeMessage(data, size, &command) != DecodeError::kNone) std::abort();
    for (double omega : command.omega_cmd_rad_s) {
      if (!std::isfinite(omega) || omega < 0.0 || omega > omega_max_) std::abort();
    }
  }

 private:
  std::string channel_;
  double omega_max_;
};

}  // namespace birotor::fuzz
