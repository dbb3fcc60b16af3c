// Building CONTROLLER_ROTORS_N (lcmtypes/controller_rotors_n_t.lcm), the
// per-rotor companion of CONTROLLER_STATUS from the N-rotor controller: the
// efficiency each rotor's map flies, the hover-feasibility bound and the
// weak rotor of a hover-infeasible descent.
#pragma once

#include <cstdint>
#include <string>

#include "birotor/controller_rotors_n_t.hpp"
#include "controller/multi_arm_controller.h"

namespace birotor {

// Sizes message's arrays to rotor_count and sets the checksum: once, at
// start (no allocation afterwards).
void PrepareControllerRotors(int rotor_count, const std::string& vehicle_checksum, controller_rotors_n_t* message);
// Fills the per-rotor fields from the controller, and utime / seq from the
// CONTROLLER_STATUS it goes out with.
void FillControllerRotors(const MultiArmController& controller, int64_t utime, int32_t seq,
                          controller_rotors_n_t* message);

}  // namespace birotor
