// libFuzzer harness for the parameter-file reader (params/): any text is
// either a valid estimator parameter file or refused with a ParamError whose
// one-line message names the file. Any other exception escaping (a YAML
// exception the reader did not catch) is a finding: it aborts the programs.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "params/estimator_config_yaml.h"
#include "params/yaml_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    birotor::ParseEstimatorConfig(text, "fuzz.yaml");
  } catch (const birotor::ParamError& error) {
    const std::string message = error.what();
    if (message.find("fuzz.yaml") == std::string::npos || message.find('\n') != std::string::npos) {
      std::fprintf(stderr, "param_file_fuzzer: message without the file or on several lines: %s\n", error.what());
      std::abort();
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "param_file_fuzzer: uncaught %s\n", error.what());
    std::abort();
  }
  return 0;
}
