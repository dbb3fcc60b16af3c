#include "controller/rotor_efficiency_estimate.h"

#include "samples/rotor_count.h"

namespace birotor {

RotorEfficiencyEstimate RotorEfficiencyReportOf(const ForceEstimate& estimate) {
  const int32_t fault_bits[kBirotorRotors] = {kStatusRotor1Fault, kStatusRotor2Fault};
  RotorEfficiencyEstimate report;
  report.utime = estimate.utime;
  report.n_rotors = kBirotorRotors;
  report.valid = (estimate.status & kStatusValid) != 0;
  report.status = estimate.status;
  for (int i = 0; i < kBirotorRotors; ++i) {
    const size_t rotor = static_cast<size_t>(i);
    report.thrust_scale[rotor] = estimate.thrust_scale[i];
    report.force_n[rotor] = estimate.force_n[i];
    report.force_std_n[rotor] = estimate.force_std_n[i];
    if ((estimate.status & fault_bits[i]) != 0) report.rotor_fault_bits |= 1 << i;
  }
  return report;
}

bool MismatchedOnly(int32_t status) {
  const int32_t not_converged_or_fed =
      kStatusConverging | kStatusInputStale | kStatusFilterReset | kStatusNoMotorInput | kStatusInputConflict;
  return (status & kStatusValid) == 0 && (status & kStatusModelMismatch) != 0 && (status & not_converged_or_fed) == 0;
}

}  // namespace birotor
