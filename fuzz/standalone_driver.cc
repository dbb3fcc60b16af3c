// Runs a libFuzzer harness without libFuzzer (g++ builds, CTest): every file
// of the corpus directories given on the command line, then a fixed number of
// deterministic pseudo-random mutations of them. Exit 0 when nothing crashed.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int main(int argc, char** argv) {
  std::vector<std::vector<uint8_t>> inputs;
  long mutations = 20000;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--mutations=", 0) == 0) {
      mutations = std::atol(arg.c_str() + 12);
      continue;
    }
    if (!std::filesystem::is_directory(arg)) {
      std::fprintf(stderr, "standalone_driver: error: '%s' is not a corpus directory\n", arg.c_str());
      return 2;
    }
    for (const auto& entry : std::filesystem::directory_iterator(arg)) {
      std::ifstream in(entry.path(), std::ios::binary);
      inputs.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
  }
  if (inputs.empty()) inputs.push_back({0});
  for (const auto& input : inputs) LLVMFuzzerTestOneInput(input.data(), input.size());
  std::mt19937_64 rng(12345);
  for (long n = 0; n < mutations; ++n) {
    std::vector<uint8_t> data = inputs[rng() % inputs.size()];
    const int edits = 1 + static_cast<int>(rng() % 8);
    for (int e = 0; e < edits; ++e) {
      switch (rng() % 4) {
        case 0:
          if (!data.empty()) data[rng() % data.size()] = static_cast<uint8_t>(rng());
          break;
        case 1:
          if (!data.empty()) data.resize(rng() % data.size());
          break;
        case 2:
          data.push_back(static_cast<uint8_t>(rng()));
          break;
        default:
          if (!data.empty()) data[rng() % data.size()] ^= static_cast<uint8_t>(1u << (rng() % 8));
          break;
      }
    }
    LLVMFuzzerTestOneInput(data.data(), data.size());
  }
  std::printf("standalone_driver: %zu corpus inputs and %ld mutations ran without a crash\n", inputs.size(), mutations);
  return 0;
}
