#include "controller/rotor_efficiency_estimate.h"

#include "samples/rotor_count.h"

namespace birotor {

RotorEfficiencyEstimate RotorEfficiencyReportOf(const ForceEstimate& estimate) {
  const int32_t fault_bits[kBirotorRotors] = {kStatusRotor1Fault, kStatusRotor2Fault};
  RotorEfficiencyEstimate report;
  report.utime = estimate.utime;
  report.n_rotors = kBirotorRotors;
  report.valid = (estimate.status & kStatusValid) != 0;
  for (int i = 0; i < kBirotorRotors; ++i) {
    report.thrust_scale[static_cast<size_t>(i)] = estimate.thrust_scale[i];
    if ((estimate.status & fault_bits[i]) != 0) report.rotor_fault_bits |= 1 << i;
  }
  return report;
}

}  // namespace birotor
