#include "evaluation/estimated_efficiency_provider.h"

#include <cmath>
#include <utility>

#include "samples/samples.h"

namespace birotor {

RotorEfficiencyEstimate EfficiencyOf(const MultiArmForceEstimate& estimate) {
  RotorEfficiencyEstimate out;
  out.utime = estimate.utime;
  out.n_rotors = estimate.n_rotors;
  out.valid = (estimate.status & kStatusValid) != 0;
  out.status = estimate.status;
  out.rotor_fault_bits = estimate.rotor_fault_bits;
  for (int i = 0; i < estimate.n_rotors; ++i) {
    const size_t rotor = static_cast<size_t>(i);
    const double force_n = estimate.force_n[rotor];
    const double relative = force_n > 0.0 ? estimate.force_std_n[rotor] / force_n : INFINITY;
    out.thrust_scale[rotor] = estimate.thrust_scale[rotor];
    out.force_n[rotor] = force_n;
    out.force_std_n[rotor] = estimate.force_std_n[rotor];
    out.thrust_scale_std[rotor] = std::abs(estimate.thrust_scale[rotor]) * relative;
  }
  return out;
}

EstimatedEfficiencyProvider::EstimatedEfficiencyProvider(const VehicleDescription& vehicle, EstimatorConfig config)
    : pipeline_(WithVehicle(std::move(config), vehicle)) {}

void EstimatedEfficiencyProvider::OnStrainN(const MultiArmStrainSample& sample) {
  if (!pipeline_.OnStrain(sample, &newest_)) return;
  ++estimates_;
  fresh_ = true;
}

bool EstimatedEfficiencyProvider::Latest(int64_t /*now_us*/, RotorEfficiencyEstimate* estimate) {
  if (!fresh_) return false;
  *estimate = EfficiencyOf(newest_);
  fresh_ = false;
  return true;
}

}  // namespace birotor
