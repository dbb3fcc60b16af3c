// Issue 37's target: signing and verifying one MOTOR_COMMAND-sized message
// under the site key in < 2 us (MessageAuthenticator, HMAC-SHA-512-256 over
// the 8-byte counter and the encoded birotor.motor_command_t).
#include <benchmark/benchmark.h>

#include <vector>

#include "birotor/motor_command_t.hpp"
#include "security/message_authenticator.h"

namespace {

std::vector<uint8_t> EncodedMotorCommand() {
  birotor::motor_command_t command{};
  command.utime = 1700000000000000;
  command.seq = 41;
  command.omega_cmd_rad_s[0] = 812.5;
  command.omega_cmd_rad_s[1] = 830.1;
  std::vector<uint8_t> bytes(command.getEncodedSize());
  command.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

birotor::SiteKey BenchmarkKey() {
  birotor::SiteKey::Bytes bytes;
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<uint8_t>(0x5a ^ i);
  return birotor::SiteKey(bytes);
}

void BM_SignMotorCommand(benchmark::State& state) {
  const std::vector<uint8_t> message = EncodedMotorCommand();
  const birotor::MessageAuthenticator authenticator(BenchmarkKey());
  uint64_t counter = 0;
  for (auto _ : state) benchmark::DoNotOptimize(authenticator.Sign(++counter, message.data(), message.size()));
  state.SetLabel(std::to_string(message.size()) + " bytes");
}
BENCHMARK(BM_SignMotorCommand);

void BM_VerifyMotorCommand(benchmark::State& state) {
  const std::vector<uint8_t> message = EncodedMotorCommand();
  const birotor::MessageAuthenticator authenticator(BenchmarkKey());
  const birotor::MessageAuthenticator::Tag tag = authenticator.Sign(41, message.data(), message.size());
  for (auto _ : state) {
    const bool ok = authenticator.Verify(41, message.data(), message.size(), tag);
    if (!ok) state.SkipWithError("a genuine tag was refused");
    benchmark::DoNotOptimize(ok);
  }
  state.SetLabel(std::to_string(message.size()) + " bytes");
}
BENCHMARK(BM_VerifyMotorCommand);

}  // namespace

BENCHMARK_MAIN();
