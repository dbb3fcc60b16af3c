// Issue 37's target: authenticating one message costs < 2 us. Signing and
// verifying one MOTOR_COMMAND-sized message under the site key
// (MessageAuthenticator, HMAC-SHA-512-256 over the 8-byte counter and the
// encoded birotor.motor_command_t), and the whole way on the wire: sealing
// a MOTOR_COMMAND into motor_command_auth_t and opening a FORCE_AUTH with
// its replay check (transport/authenticated_envelope.h,
// security/replay_guard.h).
#include <benchmark/benchmark.h>

#include <vector>

#include "birotor/force_estimate_t.hpp"
#include "birotor/motor_command_t.hpp"
#include "security/message_authenticator.h"
#include "security/replay_guard.h"
#include "transport/authenticated_envelope.h"
#include "transport/lcm_codec.h"

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

void BM_SealMotorCommand(benchmark::State& state) {
  const std::vector<uint8_t> plain = EncodedMotorCommand();
  const birotor::MessageAuthenticator authenticator(BenchmarkKey());
  const birotor::AuthenticatedChannelNames names =
      birotor::NamesOf(birotor::MakeChannelNames(), birotor::AuthenticatedChannel::kMotorCommand);
  std::vector<uint8_t> sealed;
  uint64_t counter = 0;
  for (auto _ : state) {
    if (!birotor::SealMessage(authenticator, names, 7, ++counter, plain.data(), plain.size(), &sealed)) {
      state.SkipWithError("not sealed");
    }
    benchmark::DoNotOptimize(sealed.data());
  }
  state.SetLabel(std::to_string(plain.size()) + " -> " + std::to_string(sealed.size()) + " bytes");
}
BENCHMARK(BM_SealMotorCommand);

void BM_OpenForceWithReplayCheck(benchmark::State& state) {
  birotor::force_estimate_t force{};
  force.utime = 1700000000000000;
  std::vector<uint8_t> plain;
  birotor::EncodeMessage(force, &plain);
  const birotor::MessageAuthenticator authenticator(BenchmarkKey());
  const birotor::AuthenticatedChannelNames names =
      birotor::NamesOf(birotor::MakeChannelNames(), birotor::AuthenticatedChannel::kForce);
  // A stream of sealed messages with rising counters, opened in turn.
  constexpr int kStream = 1024;
  std::vector<std::vector<uint8_t>> sealed(kStream);
  for (int i = 0; i < kStream; ++i)
    birotor::SealMessage(authenticator, names, 7, i + 1, plain.data(), plain.size(), &sealed[i]);
  std::vector<uint8_t> opened;
  birotor::ReplayGuard guard;
  int64_t k = 0;
  for (auto _ : state) {
    if (k == kStream) {  // the stream again: a fresh receiver, outside the timing
      state.PauseTiming();
      guard = birotor::ReplayGuard();
      k = 0;
      state.ResumeTiming();
    }
    const std::vector<uint8_t>& message = sealed[k++];
    uint64_t publisher = 0, counter = 0;
    const bool ok = birotor::OpenMessage(&authenticator, names, message.data(), message.size(), &opened, &publisher,
                                         &counter) == birotor::OpenVerdict::kAuthentic &&
                    guard.Admit(publisher, counter);
    if (!ok) state.SkipWithError("a genuine message was refused");
  }
  state.SetLabel(std::to_string(sealed[0].size()) + " bytes");
}
BENCHMARK(BM_OpenForceWithReplayCheck);

}  // namespace

BENCHMARK_MAIN();
