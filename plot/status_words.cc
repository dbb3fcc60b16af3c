// Status bits as words.
#include "plot/status_words.h"

#include <fmt/format.h>

#include "samples/samples.h"

namespace birotor {

const StatusBitName kStatusBitNames[] = {
    {kStatusValid, "VALID"},
    {kStatusConverging, "CONVERGING"},
    {kStatusMeasurementRejected, "REJECTED"},
    {kStatusInputStale, "STALE"},
    {kStatusRotor1Fault, "ROTOR1_FAULT"},
    {kStatusRotor2Fault, "ROTOR2_FAULT"},
    {kStatusFilterReset, "RESET"},
    {kStatusNoMotorInput, "NO_MOTOR"},
    {kStatusThrustDeficit, "THRUST_DEFICIT"},
    {kStatusInputConflict, "CONFLICT"},
    {kStatusModelMismatch, "MODEL_MISMATCH"},
};
const int kStatusBitCount = sizeof(kStatusBitNames) / sizeof(kStatusBitNames[0]);

std::string StatusWords(int32_t status) {
  std::string words;
  int32_t known = 0;
  for (int i = 0; i < kStatusBitCount; ++i) {
    const StatusBitName& name = kStatusBitNames[i];
    known |= name.bit;
    if (!(status & name.bit)) continue;
    if (!words.empty()) words += '|';
    words += name.word;
  }
  if (status & ~known) words += fmt::format("{}0x{:x}", words.empty() ? "" : "|", status & ~known);
  return words.empty() ? "none" : words;
}

}  // namespace birotor
