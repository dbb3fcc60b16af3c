// The status bits of one FORCE estimate, composed in one place from the facts
// each part returns (as PX4 EKF2 composes a sample's status): the method's
// filter facts, the pipeline's input facts, the model-consistency monitor's
// facts and the service's transport facts. No part sets a bit on another's
// estimate; they fill their facts and ComposeForceStatus decides, including
// which facts withdraw STATUS_VALID (lcmtypes/force_estimate_t.lcm).
#pragma once

#include <array>
#include <cstdint>

#include "samples/multi_arm_samples.h"
#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

// Where the method's estimate is after its last (re-)initialisation.
enum class FilterConvergence : int {
  kNoEstimate = 0,  // no estimate yet (ESTIMATOR_STATUS before the first FORCE): neither bit
  kConverging,      // STATUS_CONVERGING
  kConverged,       // STATUS_VALID unless a fact below withdraws it
};

// The method's facts (its StrainStepInfo::filter); its bits are void when
// the pipeline replaced a non-finite estimate (InputStatusFacts).
struct FilterStatusFacts {
  FilterConvergence convergence = FilterConvergence::kNoEstimate;
  bool measurement_rejected = false;                  // the strain sample failed its gate: STATUS_MEASUREMENT_REJECTED
  bool rotor_fault[kBirotorRotors] = {false, false};  // STATUS_ROTOR1_FAULT, STATUS_ROTOR2_FAULT
  bool thrust_deficit = false;                        // both rotors below the map: STATUS_THRUST_DEFICIT
};

// The pipeline's facts (EstimatorPipeline).
struct InputStatusFacts {
  bool no_motor_input = false;  // no MOTOR yet, or none before this sample: STATUS_NO_MOTOR_INPUT
  // The strain interval or the newest MOTOR's age beyond its timeout:
  // STATUS_INPUT_STALE, VALID withdrawn.
  bool stale = false;
  bool conflict = false;      // two publishers on an input: STATUS_INPUT_CONFLICT, VALID withdrawn
  bool filter_reset = false;  // the method re-initialised on this sample: STATUS_FILTER_RESET
  // The method's estimate was not finite: the pipeline reset it and
  // published the last finite estimate (forces, sigmas and thrust scales;
  // the hover force before any) instead. The filter facts are void:
  // STATUS_CONVERGING only.
  bool non_finite_replaced = false;
};

// The model-consistency monitor's facts (ModelConsistencyMonitor::Judge);
// all false for a method it does not judge (no innovations) or when it is off.
struct ConsistencyStatusFacts {
  // Mismatch raised: STATUS_MODEL_MISMATCH; VALID and THRUST_DEFICIT withdrawn.
  bool mismatch = false;
  // Not yet confirmed (no mismatch either): THRUST_DEFICIT withdrawn, and
  // VALID with unconfirmed_withholds_valid (option valid_needs_confirmation).
  bool model_unconfirmed = false;
  bool unconfirmed_withholds_valid = false;
  // The arm mode has not yet confirmed the tip mass: each published force
  // sigma carries the tip mass's prior (tip_mass_force_std_n, added in
  // quadrature by PublishedForceStd); VALID withdrawn with
  // tip_mass_withholds_valid (option arm_mode_valid_needs_reading).
  bool tip_mass_unconfirmed = false;
  bool tip_mass_withholds_valid = false;
  // sigma_tip = sigma_r m_p g: sigma_r the prior's (arm_mode_unconfirmed_tip_mass_std)
  // or the learned one (ArmModeState::force_tip_mass_std) [N].
  double tip_mass_force_std_n = 0;
  // The gauge offsets' departure from their anchor along the common-force
  // direction, as the force on rotor i a payload would make it (option
  // offset_departure_in_sigma_above; 0 on the ground, and before a free-flight
  // judgement) [N]; added in quadrature by PublishedForceStd.
  std::array<double, kMaxSampleArms> offset_force_std_n{};
};

// The estimator service's facts (nodes/estimator_service).
struct TransportStatusFacts {
  // A FORCE this daemon did not publish arrived on its FORCE channel within
  // foreign_force_hold_s: STATUS_INPUT_CONFLICT, VALID withdrawn.
  bool foreign_force = false;
  // ESTIMATOR_STATUS only: no strain packet for stale_input_wall_s on the
  // host clock: STATUS_INPUT_STALE, VALID withdrawn.
  bool no_strain_on_wall_clock = false;
};

struct ForceStatusFacts {
  FilterStatusFacts filter;
  InputStatusFacts input;
  ConsistencyStatusFacts consistency;
  TransportStatusFacts transport;
};

// The STATUS_* bit set of the estimate these facts describe (the one writer
// of force_estimate_t::status; tools/status_owner.py checks it).
int32_t ComposeForceStatus(const ForceStatusFacts& facts);

// The bits of the method's facts; deficit_explained (a mismatch, or a model
// not yet confirmed) withdraws THRUST_DEFICIT. Inline and without a branch
// per fact: it runs on every strain sample (benchmarks/estimator_benchmark.cc).
inline int32_t FilterStatusBits(const FilterStatusFacts& f, bool deficit_explained) {
  return (f.convergence == FilterConvergence::kConverged) * kStatusValid |
         (f.convergence == FilterConvergence::kConverging) * kStatusConverging |
         f.measurement_rejected * kStatusMeasurementRejected | f.rotor_fault[0] * kStatusRotor1Fault |
         f.rotor_fault[1] * kStatusRotor2Fault | (f.thrust_deficit && !deficit_explained) * kStatusThrustDeficit;
}

// The bits of the method's facts alone (no pipeline, consistency or
// transport facts): ComposeForceStatus of ForceStatusFacts holding only
// `facts`, without building one (ForceEstimator::AddStrain).
inline int32_t ComposeFilterStatus(const FilterStatusFacts& facts) { return FilterStatusBits(facts, false); }

// Whether any fact withdraws STATUS_VALID from a converged filter's estimate.
bool ValidWithdrawn(const ForceStatusFacts& facts);

// The published one-sigma of rotor `rotor`'s force from the method's [N]:
// the method's with the offsets' departure (offset_force_std_n) and, while
// the tip mass is unconfirmed, its sigma added in quadrature (std::hypot);
// with neither, the method's, unchanged.
double PublishedForceStd(double method_force_std_n, const ForceStatusFacts& facts, int rotor);

// The method's facts of an N-rotor estimate (estimator/multi_arm_ekf.h),
// with the birotor's meaning of each: converged once every force sigma fell
// below converged_force_std_n (VALID), else CONVERGING; the strain sample
// gated (MEASUREMENT_REJECTED); rotor i weaker than the others
// (rotor_fault_bits bit i); every rotor below its map (THRUST_DEFICIT).
struct MultiArmFilterFacts {
  FilterConvergence convergence = FilterConvergence::kNoEstimate;
  bool measurement_rejected = false;
  std::array<bool, kMaxSampleArms> rotor_fault{};
  bool thrust_deficit = false;
};

// force_estimate_n_t's status and rotor_fault_bits (from the method's facts
// alone in ComposeMultiArmFilterStatus).
struct MultiArmStatusBits {
  int32_t status = 0;
  int32_t rotor_fault_bits = 0;
};
MultiArmStatusBits ComposeMultiArmFilterStatus(const MultiArmFilterFacts& facts, int n_rotors);

// The published status of an N-rotor estimate: ComposeForceStatus's rules on
// the method's facts with the pipeline's, its model-consistency monitor's
// (MODEL_MISMATCH withdraws VALID and THRUST_DEFICIT, a tip mass awaiting
// the arm mode withholds VALID with arm_mode_valid_needs_reading; the
// pipeline widens each sigma by the tip mass's) and the service's; the rotor bits
// are the method's, void (none) when the pipeline replaced a non-finite
// estimate.
MultiArmStatusBits ComposeMultiArmForceStatus(const MultiArmFilterFacts& filter, const InputStatusFacts& input,
                                              const ConsistencyStatusFacts& consistency,
                                              const TransportStatusFacts& transport, int n_rotors);

}  // namespace birotor
