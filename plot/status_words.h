// The status bits of force_estimate_t (lcmtypes/force_estimate_t.lcm) as the
// words the monitor prints and the plots label, in one table.
#pragma once

#include <cstdint>
#include <string>

#include "samples/samples.h"

namespace birotor {

struct StatusBitName {
  int32_t bit;
  const char* word;
};

// Bits that mean something went wrong (an input, a rotor, the filter): the
// monitor lists when each was first set, the plots mark it with a line.
inline constexpr int32_t kAlarmStatusBits =
    kStatusInputStale | kStatusRotor1Fault | kStatusRotor2Fault | kStatusFilterReset;

// Every bit of force_estimate_t, in the order of the .lcm file.
extern const StatusBitName kStatusBitNames[];
extern const int kStatusBitCount;

// Status bits as words, e.g. "VALID" or "CONVERGING|NO_MOTOR"; "none" for 0;
// unknown bits as hex ("VALID|0x400").
std::string StatusWords(int32_t status);

}  // namespace birotor
