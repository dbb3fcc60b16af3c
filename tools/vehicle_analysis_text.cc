#include "tools/vehicle_analysis_text.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace birotor {
namespace {

std::string Format(const char* format, ...) {
  char buffer[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof(buffer), format, args);
  va_end(args);
  return buffer;
}

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
  return out.empty() ? "-" : out;
}

double Degrees(double angle_rad) { return angle_rad * 180.0 / M_PI; }

std::string HoverText(const VehicleDescription& vehicle, const VehicleAnalysis& analysis) {
  std::string out = Format("Hover equilibrium (phi = 0, %s, residual %.2g)\n\n",
                           analysis.hover.converged ? "converged" : "NOT converged", analysis.hover.residual);
  out += "| arm | alpha [deg] | theta [deg] | lever l_i [m] | gauge | f_i [N] | rigid allocation [N] | b_i [rad] |\n";
  out += "|---|---|---|---|---|---|---|---|\n";
  for (int i = 0; i < vehicle.arm_count; ++i) {
    const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
    out += Format("| %d | %.1f | %.1f | %.4f | %s | %.4f | %.4f | %.7f |\n", i + 1, Degrees(arm.angle_rad),
                  Degrees(arm.thrust_angle_rad), arm.ThrustLeverM(), arm.has_gauge ? "yes" : "no",
                  analysis.hover.force_n(i), analysis.hover.allocation_force_n(i), analysis.hover.deflection_rad(i));
  }
  return out;
}

}  // namespace

bool VehicleWithoutGauges(const VehicleDescription& vehicle, const std::vector<int>& arms_1based,
                          VehicleDescription* out, std::string* why) {
  *out = vehicle;
  std::vector<std::string> removed;
  for (auto it = arms_1based.begin(); it != arms_1based.end(); ++it) {
    const int arm = *it;
    if (arm < 1 || arm > vehicle.arm_count) {
      *why = Format("arm %d is not an arm of %s (arms 1 to %d)", arm, vehicle.name.c_str(), vehicle.arm_count);
      return false;
    }
    ArmDescription& description = out->arms[static_cast<size_t>(arm - 1)];
    if (std::find(arms_1based.begin(), it, arm) != it) {
      *why = Format("arm %d is named twice", arm);
      return false;
    }
    if (!description.has_gauge) {
      *why = Format("arm %d of %s has no gauge to remove", arm, vehicle.name.c_str());
      return false;
    }
    description.has_gauge = false;
    removed.push_back(std::to_string(arm));
  }
  if (out->GaugeCount() == 0) {
    *why = "no gauge would remain on " + vehicle.name + " (the analysis is of the gauges)";
    return false;
  }
  if (!removed.empty())
    out->name += (removed.size() == 1 ? ", no gauge on arm " : ", no gauge on arms ") + Join(removed);
  return true;
}

std::string MeasurementSetLabel(const VehicleDescription& vehicle, VehicleMeasurementSet measured) {
  std::vector<std::string> gauges;
  for (int i = 0; i < vehicle.arm_count; ++i)
    if (vehicle.arms[static_cast<size_t>(i)].has_gauge) gauges.push_back("b" + std::to_string(i + 1));
  switch (measured) {
    case VehicleMeasurementSet::kGauges:
      return "gauges (" + Join(gauges) + ")";
    case VehicleMeasurementSet::kGaugesImu:
      return "gauges (" + Join(gauges) + ") + IMU (gyro, accelerometer)";
    case VehicleMeasurementSet::kPosition:
      return "position (x, z)";
    case VehicleMeasurementSet::kAllMechanical:
      return "all mechanical states";
  }
  return "?";
}

std::string ForceDirectionText(const Eigen::VectorXd& direction) {
  std::string out = "[";
  for (int i = 0; i < direction.size(); ++i) out += Format("%s%.2f", i == 0 ? "" : ", ", direction(i) + 0.0);
  return out + "]";
}

std::string VehicleAnalysisText(const VehicleDescription& vehicle, const VehicleAnalysis& analysis) {
  std::string out =
      Format("Vehicle: %s (%d arms, %d gauges)\n\n", analysis.name.c_str(), analysis.arm_count, analysis.gauge_count);
  out += HoverText(vehicle, analysis);
  out += "\nArm modes at hover\n\n| mode | frequency [Hz] | damping ratio |\n|---|---|---|\n";
  for (size_t k = 0; k < analysis.modes.size(); ++k)
    out += Format("| %zu | %.3f | %.4f |\n", k + 1, analysis.modes[k].frequency_hz, analysis.modes[k].damping_ratio);
  const SubspaceReport& ctrb = analysis.controllability;
  out += Format("\nControllability from the %d forces: rank %d / %d; uncontrollable: %s\n", analysis.arm_count,
                ctrb.rank, ctrb.state_size, Join(ctrb.hidden_states).c_str());
  out += Format(
      "\nObservability with the forces as constant states (%d states; balanced staircase test, relative rank\n"
      "tolerance 1e-8; sigma = singular values of the scaled observability matrix)\n\n",
      analysis.observability.empty() ? 0 : analysis.observability[0].report.state_size);
  out +=
      "| measured | rank | unobservable states | forces observable | unobservable force combination | "
      "sigma_rank / sigma_max |\n|---|---|---|---|---|---|\n";
  for (const ForceObservability& r : analysis.observability) {
    std::vector<std::string> directions;
    for (const Eigen::VectorXd& d : r.unobservable_force_directions) directions.push_back(ForceDirectionText(d));
    const Eigen::VectorXd& sigma = r.report.singular_values;
    out += Format("| %s | %d / %d | %s | %s | %s | %.3g |\n", MeasurementSetLabel(vehicle, r.measured).c_str(),
                  r.report.rank, r.report.state_size, Join(r.report.hidden_states).c_str(),
                  r.forces_observable ? "yes" : "no", Join(directions).c_str(),
                  r.report.rank > 0 ? sigma(r.report.rank - 1) / sigma(0) : 0.0);
  }
  return out;
}

}  // namespace birotor
