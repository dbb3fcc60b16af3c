// The message of the ParamError a reader throws, for the tests that check a
// refused file names its file, key and range.
#pragma once

#include <string>

#include "params/yaml_reader.h"

namespace birotor {
namespace testing {

// What read() throws as a ParamError; empty if it reads without one.
template <typename Read>
std::string ParamErrorOf(Read read) {
  try {
    read();
  } catch (const ParamError& e) {
    return e.what();
  }
  return "";
}

}  // namespace testing
}  // namespace birotor
