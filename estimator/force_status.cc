// The one composer of a FORCE estimate's status (force_status.h).
#include "estimator/force_status.h"

#include <cmath>

namespace birotor {

bool ValidWithdrawn(const ForceStatusFacts& facts) {
  const InputStatusFacts& input = facts.input;
  const ConsistencyStatusFacts& model = facts.consistency;
  const TransportStatusFacts& transport = facts.transport;
  // VALID means converged, fresh, from one publisher per input and per
  // FORCE channel, and consistent with the parameter file.
  return input.stale || input.conflict || model.mismatch ||
         (model.model_unconfirmed && model.unconfirmed_withholds_valid) ||
         (model.tip_mass_unconfirmed && model.tip_mass_withholds_valid) || transport.foreign_force ||
         transport.no_strain_on_wall_clock;
}

int32_t ComposeForceStatus(const ForceStatusFacts& facts) {
  // CONVERGING alone from the method for an estimate the pipeline replaced.
  int32_t status =
      facts.input.non_finite_replaced
          ? kStatusConverging
          : FilterStatusBits(facts.filter, facts.consistency.mismatch || facts.consistency.model_unconfirmed);
  if (facts.input.no_motor_input) status |= kStatusNoMotorInput;
  if (facts.input.stale || facts.transport.no_strain_on_wall_clock) status |= kStatusInputStale;
  if (facts.input.conflict || facts.transport.foreign_force) status |= kStatusInputConflict;
  if (facts.input.filter_reset) status |= kStatusFilterReset;
  if (facts.consistency.mismatch) status |= kStatusModelMismatch;
  if (ValidWithdrawn(facts)) status &= ~kStatusValid;
  return status;
}

double PublishedForceStd(double method_force_std_n, const ForceStatusFacts& facts, int rotor) {
  const double offsets_n = facts.consistency.offset_force_std_n[static_cast<size_t>(rotor)];
  const double std_n = offsets_n > 0 ? std::hypot(method_force_std_n, offsets_n) : method_force_std_n;
  if (!facts.consistency.tip_mass_unconfirmed) return std_n;
  return std::hypot(std_n, facts.consistency.tip_mass_force_std_n);
}

MultiArmStatusBits ComposeMultiArmFilterStatus(const MultiArmFilterFacts& facts, int n_rotors) {
  // The birotor's rules for the method's bits (FilterStatusBits); the rotor
  // bits move to rotor_fault_bits, as transport/counted_messages.cc maps them.
  FilterStatusFacts shared;
  shared.convergence = facts.convergence;
  shared.measurement_rejected = facts.measurement_rejected;
  shared.thrust_deficit = facts.thrust_deficit;
  MultiArmStatusBits out;
  out.status = FilterStatusBits(shared, false);
  for (int i = 0; i < n_rotors && i < kMaxSampleArms; ++i) {
    out.rotor_fault_bits |= static_cast<int32_t>(facts.rotor_fault[static_cast<size_t>(i)]) << i;
  }
  return out;
}

MultiArmStatusBits ComposeMultiArmForceStatus(const MultiArmFilterFacts& filter, const InputStatusFacts& input,
                                              const ConsistencyStatusFacts& consistency,
                                              const TransportStatusFacts& transport, int n_rotors) {
  ForceStatusFacts facts;
  facts.filter.convergence = filter.convergence;
  facts.filter.measurement_rejected = filter.measurement_rejected;
  facts.filter.thrust_deficit = filter.thrust_deficit;
  facts.input = input;
  facts.consistency = consistency;
  facts.transport = transport;
  MultiArmStatusBits out;
  out.status = ComposeForceStatus(facts);
  if (!input.non_finite_replaced) out.rotor_fault_bits = ComposeMultiArmFilterStatus(filter, n_rotors).rotor_fault_bits;
  return out;
}

}  // namespace birotor
