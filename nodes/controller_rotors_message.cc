// Building CONTROLLER_ROTORS_N from the N-rotor controller.
#include "nodes/controller_rotors_message.h"

#include <cstddef>
#include <limits>

namespace birotor {

void PrepareControllerRotors(int rotor_count, const std::string& vehicle_checksum, controller_rotors_n_t* message) {
  message->n_rotors = static_cast<int8_t>(rotor_count);
  message->vehicle_checksum = vehicle_checksum;
  message->efficiency.assign(static_cast<size_t>(rotor_count), 1.0);
  message->feasibility_bound.assign(static_cast<size_t>(rotor_count), 0.0);
  message->weak_rotor = 0;
  message->weak_efficiency = std::numeric_limits<double>::quiet_NaN();
}

void FillControllerRotors(const MultiArmController& controller, int64_t utime, int32_t seq,
                          controller_rotors_n_t* message) {
  const HoverFeasibility& feasibility = controller.feasibility();
  const RotorEfficiencies& efficiency = controller.flown_efficiency();
  message->utime = utime;
  message->seq = seq;
  for (int i = 0; i < message->n_rotors; ++i) {
    const size_t rotor = static_cast<size_t>(i);
    message->efficiency[rotor] = efficiency[rotor];
    message->feasibility_bound[rotor] = feasibility.FeasibilityBound(i);
  }
  const bool infeasible = feasibility.infeasible();
  message->weak_rotor = static_cast<int8_t>(infeasible ? feasibility.weak_rotor() + 1 : 0);
  message->weak_efficiency = infeasible ? feasibility.weak_efficiency() : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace birotor
