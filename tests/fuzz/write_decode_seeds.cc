// Writes the decode fuzzer's seeds that follow the example messages of
// tests/transport (fuzz/decode_targets.h has the selector rule):
//   - one per later target, named after its type: selector 0x80 + its index,
//     then the encoded example message;
//   - the two seeds of estimator_status_t, the one first-nine type that has
//     grown since its seeds were written: "status" (selector 7) and the
//     reproducer "status_gauge_source_length_int_min" (selector 0xFA, 250 % 9
//     = 7; gauge_offset_source's length INT_MIN, CodecTest.
//     CorruptLengthOfTheLaterStringsIsRejected).
// Run by hand when a type is added or changes:
//   build/tests/fuzz/write_decode_seeds fuzz/corpus/decode_fuzzer
// (tests/fuzz/decode_corpus_test.cc checks the corpus against the table).
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "fuzz/decode_targets.h"
#include "tests/transport/sealed_and_status_test_messages.h"

namespace birotor::fuzz {
namespace {

bool WriteFile(const std::filesystem::path& path, uint8_t selector, const std::vector<uint8_t>& packet) {
  std::ofstream out(path, std::ios::binary);
  out.put(static_cast<char>(selector));
  out.write(reinterpret_cast<const char*>(packet.data()), static_cast<std::streamsize>(packet.size()));
  return static_cast<bool>(out);
}

// Writes the seed of Msg into directory; false if Msg is not a later target.
template <class Msg>
bool WriteSeed(const std::filesystem::path& directory) {
  for (size_t i = 0; i < kNumLaterTargets; ++i) {
    const DecodeTarget& target = kLaterTargets[i];
    if (target.fingerprint() != FingerprintOf<Msg>()) continue;
    return WriteFile(directory / target.type_name, static_cast<uint8_t>(kFirstLaterSelector + i),
                     transport_test::Encode(transport_test::MakeTestMessage<Msg>()));
  }
  return false;
}

// The example status, and the same with an empty gauge_offset_source whose
// length field says INT_MIN (found through a marker string in its place).
bool WriteStatusSeeds(const std::filesystem::path& directory) {
  const estimator_status_t status = transport_test::MakeTestMessage<estimator_status_t>();
  constexpr uint8_t kStatusSelector = 7, kReproducerSelector = 0xFA;
  const char* const marker = "gauge-offset-source-marker";
  estimator_status_t marked = status;
  marked.gauge_offset_source = marker;
  std::vector<uint8_t> corrupt = transport_test::Encode(marked);
  const auto at = std::search(corrupt.begin(), corrupt.end(), marker, marker + std::strlen(marker));
  if (at == corrupt.end()) return false;
  const auto length_offset = static_cast<size_t>(at - corrupt.begin()) - 4;
  corrupt.erase(at, at + static_cast<std::ptrdiff_t>(std::strlen(marker)));  // "": only the NUL stays
  corrupt[length_offset] = 0x80;                                             // INT_MIN, big-endian
  std::fill(corrupt.begin() + static_cast<std::ptrdiff_t>(length_offset) + 1,
            corrupt.begin() + static_cast<std::ptrdiff_t>(length_offset) + 4, 0);
  return WriteFile(directory / "status", kStatusSelector, transport_test::Encode(status)) &&
         WriteFile(directory / "status_gauge_source_length_int_min", kReproducerSelector, corrupt);
}

template <class... Msgs>
int WriteSeeds(const std::filesystem::path& directory) {
  const bool written[] = {WriteSeed<Msgs>(directory)...};
  int failures = 0;
  for (bool ok : written) failures += ok ? 0 : 1;
  return failures;
}

}  // namespace
}  // namespace birotor::fuzz

int main(int argc, char** argv) {
  if (argc != 2 || !std::filesystem::is_directory(argv[1])) {
    std::fprintf(stderr, "usage: write_decode_seeds CORPUS_DIRECTORY\n");
    return 2;
  }
  using namespace birotor;  // NOLINT: the type list below
  const int failures =
      fuzz::WriteSeeds<strain_n_t, motor_n_t, loadcell_n_t, truth_n_t, force_estimate_n_t, motor_command_n_t,
                       vehicle_description_t, estimator_learned_n_t, controller_rotors_n_t, force_estimate_n_auth_t,
                       motor_command_n_auth_t, motor_command_t, setpoint_t, controller_status_t, guard_status_t,
                       motor_command_auth_t, setpoint_auth_t, pose_auth_t, force_estimate_auth_t>(argv[1]) +
      (fuzz::WriteStatusSeeds(argv[1]) ? 0 : 1);
  if (failures != 0) std::fprintf(stderr, "write_decode_seeds: %d seeds not written\n", failures);
  std::printf("write_decode_seeds: %zu seeds in %s\n", birotor::fuzz::kNumLaterTargets + 2, argv[1]);
  return failures == 0 ? 0 : 1;
}
