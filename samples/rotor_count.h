// The birotor's rotor count: one rotor, one elastic arm and one strain gauge
// on each side. Every per-rotor (per-arm, per-gauge) array of the birotor's
// samples, wire types, filters and fits is sized by it, never by a literal 2.
// A vehicle with another count is a VehicleDescription
// (model/vehicle_description.h, up to kMaxArms) on the N-arm types.
#pragma once

namespace birotor {

inline constexpr int kBirotorRotors = 2;

}  // namespace birotor
