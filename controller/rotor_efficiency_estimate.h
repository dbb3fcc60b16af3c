// Each rotor's thrust efficiency as an estimator reports it, for any rotor
// count (the content of force_estimate_n_t; the birotor's FORCE converts to
// it, RotorEfficiencyReportOf): what MultiArmController flies on and what
// ForceFloorEvidence and EfficiencyConditioner read. Plain data.
#pragma once

#include <array>
#include <cstdint>

#include "model/vehicle_description.h"
#include "samples/samples.h"

namespace birotor {

// Rotor i is arm i of the vehicle description (entries from n_rotors on unused).
struct RotorEfficiencyEstimate {
  int64_t utime = -1;                               // vehicle clock [us]; -1: none
  int n_rotors = 0;                                 // must be the vehicle's arm_count
  std::array<double, kMaxArms> thrust_scale{};      // real thrust / c_T,i omega_i^2 [1]
  std::array<double, kMaxArms> thrust_scale_std{};  // its one-sigma [1]
  std::array<double, kMaxArms> force_n{};           // rotor i's estimated thrust [N]
  std::array<double, kMaxArms> force_std_n{};       // its one-sigma [N]
  bool valid = false;                               // the estimator's STATUS_VALID
  int32_t status = 0;                               // the vehicle-wide STATUS_* bits (samples/samples.h StatusBit)
  int32_t rotor_fault_bits = 0;                     // bit i: rotor i + 1 faulty
};

// The birotor's FORCE as such a report: 2 rotors, VALID from kStatusValid,
// the status as it is, bit i from kStatusRotor1Fault / kStatusRotor2Fault,
// the scales, forces and force sigmas as they are (scale sigmas 0: FORCE
// gives the force's, not the scale's).
RotorEfficiencyEstimate RotorEfficiencyReportOf(const ForceEstimate& estimate);

// A report whose VALID MODEL_MISMATCH alone withdrew: the model cannot
// explain the data, but the filter is converged, fresh, from one publisher
// and driven by the motors (none of CONVERGING, INPUT_STALE, FILTER_RESET,
// NO_MOTOR_INPUT, INPUT_CONFLICT).
bool MismatchedOnly(int32_t status);

}  // namespace birotor
