// The model analysis of any vehicle description: hover, arm modes,
// controllability from the rotor forces, and which rotor forces each set of
// sensors can observe (thesis ch. 4 for the birotor, section 7.3.2 for three
// rotors). Returns structs; birotor-analyze's formatter prints them.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "model/multi_arm_linearization.h"
#include "model/observability.h"
#include "model/vehicle_description.h"

namespace birotor {

// Measurement sets of the observability table, on the augmented state
// [q; v; f] linearized at hover.
enum class VehicleMeasurementSet : int {
  kGauges = 0,         // b_i of every arm with has_gauge (gauge_scale s_i b_i; offsets known)
  kGaugesImu = 1,      // the gauges, the gyro phi_dot and the accelerometer at the body centre,
                       // specific force in body axes R(phi)^T (p_ddot + [0, g])
  kPosition = 2,       // x, z (the birotor analysis's "x,z" set: motion capture position)
  kAllMechanical = 3,  // every q and v (the birotor analysis's "all ten mechanical states")
};
inline constexpr VehicleMeasurementSet kVehicleMeasurementSets[] = {
    VehicleMeasurementSet::kGauges, VehicleMeasurementSet::kGaugesImu, VehicleMeasurementSet::kPosition,
    VehicleMeasurementSet::kAllMechanical};

// Singular values of the hidden force block below this (the hidden basis is
// orthonormal, so its entries are at most 1) count as zero.
inline constexpr double kForceDirectionTolerance = 1e-6;

// Which forces one measurement set observes.
struct ForceObservability {
  VehicleMeasurementSet measured = VehicleMeasurementSet::kGauges;
  SubspaceReport report;           // rank of the (3N + 6)-state augmented system, hidden axes, singular values
  bool forces_observable = false;  // every f_i observable (no hidden direction has a force part)
  // Orthonormal basis of the force parts of the hidden subspace: moving the
  // forces along one of these (with the states it drags along) leaves the
  // measurements unchanged, so only the combinations orthogonal to them are
  // observed. Each is unit length with its first non-zero entry positive.
  std::vector<Eigen::VectorXd> unobservable_force_directions;
};

struct VehicleAnalysis {
  std::string name;
  int arm_count = 0;
  int gauge_count = 0;
  MultiArmHover hover;
  std::vector<Mode> modes;                        // arm modes at hover, by frequency
  SubspaceReport controllability;                 // of the 2n mechanical states from the N forces
  std::vector<ForceObservability> observability;  // one per kVehicleMeasurementSets entry
};

// Rows C of one measurement set on [q; v; f] at hover (aug = [[A, B], [0, 0]]).
// The accelerometer rows, linearized at phi = 0, p_ddot = 0:
//   d s_x = d x_ddot + g d phi,  d s_z = d z_ddot,  with d p_ddot the rows of aug.
Eigen::MatrixXd VehicleMeasurementMatrix(const VehicleDescription& vehicle, const Eigen::MatrixXd& aug,
                                         VehicleMeasurementSet measured);

// The observability of the forces from one set (model/observability.h's
// balanced staircase test; its relative rank tolerance is 1e-8).
ForceObservability AnalyzeForceObservability(const VehicleDescription& vehicle, const Eigen::MatrixXd& aug,
                                             VehicleMeasurementSet measured);

VehicleAnalysis AnalyzeVehicle(const VehicleDescription& vehicle);

}  // namespace birotor
