#include "model/vehicle_analysis.h"

#include <Eigen/SVD>

#include "model/multi_arm_dynamics.h"

namespace birotor {
namespace {

// Orthonormal basis of the column space of the hidden basis's force rows,
// each sign-normalised (first entry above the tolerance positive).
std::vector<Eigen::VectorXd> ForceDirections(const Eigen::MatrixXd& hidden, int arm_count) {
  std::vector<Eigen::VectorXd> directions;
  if (hidden.cols() == 0) return directions;
  const Eigen::MatrixXd force_rows = hidden.bottomRows(arm_count);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(force_rows, Eigen::ComputeFullU);
  for (int k = 0; k < svd.singularValues().size(); ++k) {
    if (svd.singularValues()(k) <= kForceDirectionTolerance) continue;
    Eigen::VectorXd direction = svd.matrixU().col(k);
    for (int i = 0; i < arm_count; ++i) {
      if (std::abs(direction(i)) <= kForceDirectionTolerance) continue;
      if (direction(i) < 0) direction = -direction;
      break;
    }
    directions.push_back(direction);
  }
  return directions;
}

}  // namespace

Eigen::MatrixXd VehicleMeasurementMatrix(const VehicleDescription& vehicle, const Eigen::MatrixXd& aug,
                                         VehicleMeasurementSet measured) {
  const int n = CoordinateCount(vehicle), states = static_cast<int>(aug.cols());
  std::vector<Eigen::RowVectorXd> rows;
  const auto unit = [&](int state, double scale) { rows.push_back(scale * Eigen::RowVectorXd::Unit(states, state)); };
  switch (measured) {
    case VehicleMeasurementSet::kGauges:
    case VehicleMeasurementSet::kGaugesImu:
      for (int i = 0; i < vehicle.arm_count; ++i) {
        const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
        if (arm.has_gauge) unit(DeflectionIndex(i), arm.gauge_scale);
      }
      if (measured == VehicleMeasurementSet::kGauges) break;
      unit(n + kPhi, 1.0);  // gyro
      rows.push_back(aug.row(n + kX) + vehicle.gravity_m_s2 * Eigen::RowVectorXd::Unit(states, kPhi));
      rows.push_back(aug.row(n + kZ));
      break;
    case VehicleMeasurementSet::kPosition:
      unit(kX, 1.0);
      unit(kZ, 1.0);
      break;
    case VehicleMeasurementSet::kAllMechanical:
      for (int j = 0; j < 2 * n; ++j) unit(j, 1.0);
      break;
  }
  Eigen::MatrixXd c(static_cast<int>(rows.size()), states);
  for (size_t r = 0; r < rows.size(); ++r) c.row(static_cast<int>(r)) = rows[r];
  return c;
}

ForceObservability AnalyzeForceObservability(const VehicleDescription& vehicle, const Eigen::MatrixXd& aug,
                                             VehicleMeasurementSet measured) {
  ForceObservability out;
  out.measured = measured;
  out.report = AnalyzeObservability(aug, VehicleMeasurementMatrix(vehicle, aug, measured),
                                    MultiArmStateNames(vehicle.arm_count));
  out.unobservable_force_directions = ForceDirections(out.report.hidden_basis, vehicle.arm_count);
  out.forces_observable = out.unobservable_force_directions.empty();
  return out;
}

VehicleAnalysis AnalyzeVehicle(const VehicleDescription& vehicle) {
  VehicleAnalysis out;
  out.name = vehicle.name;
  out.arm_count = vehicle.arm_count;
  out.gauge_count = vehicle.GaugeCount();
  out.hover = SolveMultiArmHover(vehicle);
  const MultiArmLinearModel lin = LinearizeMultiArmAtHover(vehicle, out.hover);
  out.modes = OscillatoryModes(lin.a);
  std::vector<std::string> mechanical = MultiArmStateNames(vehicle.arm_count);
  mechanical.resize(static_cast<size_t>(lin.a.rows()));
  out.controllability = AnalyzeControllability(lin.a, lin.b, mechanical);
  const Eigen::MatrixXd aug = AugmentMultiArmWithForces(lin);
  for (VehicleMeasurementSet measured : kVehicleMeasurementSets)
    out.observability.push_back(AnalyzeForceObservability(vehicle, aug, measured));
  return out;
}

}  // namespace birotor
