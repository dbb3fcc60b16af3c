#include "model/vehicle_description.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace birotor {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string Number(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

std::string ArmKey(int i, const std::string& field) { return "arms[" + std::to_string(i) + "]." + field; }

// The real fields of a description, by their names in the struct and in the
// N-arm file (docs/vehicle-description.md); angles are compared modulo 2 pi.
const std::vector<std::pair<const char*, double VehicleDescription::*>>& BodyReals() {
  using V = VehicleDescription;
  static const std::vector<std::pair<const char*, double V::*>> fields = {
      {"body_mass_kg", &V::body_mass_kg},
      {"body_inertia_kg_m2", &V::body_inertia_kg_m2},
      {"gravity_m_s2", &V::gravity_m_s2},
      {"omega_max_rad_s", &V::omega_max_rad_s},
      {"turbulence_std", &V::turbulence_std},
      {"turbulence_corr_time_s", &V::turbulence_corr_time_s},
      {"gauge_offset_std_rad", &V::gauge_offset_std_rad},
      {"gauge_drift_psd_rad2_s", &V::gauge_drift_psd_rad2_s},
  };
  return fields;
}

const std::vector<std::pair<const char*, double ArmDescription::*>>& ArmReals() {
  using A = ArmDescription;
  static const std::vector<std::pair<const char*, double A::*>> fields = {
      {"angle_rad", &A::angle_rad},
      {"length_m", &A::length_m},
      {"thrust_angle_rad", &A::thrust_angle_rad},
      {"stiffness_n_m_rad", &A::stiffness_n_m_rad},
      {"damping_n_m_s_rad", &A::damping_n_m_s_rad},
      {"tip_mass_kg", &A::tip_mass_kg},
      {"thrust_coeff_n_s2_rad2", &A::thrust_coeff_n_s2_rad2},
      {"motor_time_constant_s", &A::motor_time_constant_s},
      {"gauge_scale", &A::gauge_scale},
      {"gauge_offset_rad", &A::gauge_offset_rad},
  };
  return fields;
}

// The helpers below need 2 <= arm_count <= kMaxArms (PlausibilityProblems
// says so when it is not).
bool ValidArmCount(const VehicleDescription& d) { return d.arm_count >= kBirotorArmCount && d.arm_count <= kMaxArms; }

bool IsAngle(const std::string& name) { return name == "angle_rad" || name == "thrust_angle_rad"; }

bool Agree(const std::string& name, double a, double b) {
  if (IsAngle(name)) return std::fabs(std::remainder(a - b, 2.0 * kPi)) <= kDescriptionTolerance;
  return a == b || std::fabs(a - b) <= kDescriptionTolerance * std::max(std::fabs(a), std::fabs(b));
}

std::string Differs(const std::string& key, const std::string& a, const std::string& b) {
  return key + ": " + a + " vs " + b;
}

std::string FirstArmDifference(int i, const ArmDescription& a, const ArmDescription& b) {
  for (const auto& [name, field] : ArmReals()) {
    if (!Agree(name, a.*field, b.*field)) return Differs(ArmKey(i, name), Number(a.*field), Number(b.*field));
  }
  if (a.spin != b.spin) return Differs(ArmKey(i, "spin"), Number(a.spin), Number(b.spin));
  if (a.has_gauge != b.has_gauge) {
    return Differs(ArmKey(i, "has_gauge"), a.has_gauge ? "true" : "false", b.has_gauge ? "true" : "false");
  }
  return "";
}

// Non-positive or non-finite values that make the rest meaningless.
void CheckPositive(const std::string& key, double value, const std::string& unit, std::vector<std::string>* problems) {
  if (!(std::isfinite(value) && value > 0.0)) {
    problems->push_back(key + ": " + Number(value) + " " + unit + " is not a positive finite number (allowed: > 0 " +
                        unit + ")");
  }
}

void CheckFinite(const std::string& key, double value, std::vector<std::string>* problems) {
  if (!std::isfinite(value)) problems->push_back(key + ": " + Number(value) + " is not finite (allowed: a number)");
}

// arm_count, then every field on its own: the problems that make the
// allocation and the hover meaningless.
std::vector<std::string> FieldProblems(const VehicleDescription& d) {
  std::vector<std::string> problems;
  if (!ValidArmCount(d)) {
    problems.push_back("arm_count: " + Number(d.arm_count) + " arms (allowed: [" + Number(kBirotorArmCount) + ", " +
                       Number(kMaxArms) + "])");
    return problems;
  }
  CheckPositive("body_mass_kg", d.body_mass_kg, "kg", &problems);
  CheckPositive("body_inertia_kg_m2", d.body_inertia_kg_m2, "kg m^2", &problems);
  CheckPositive("omega_max_rad_s", d.omega_max_rad_s, "rad/s", &problems);
  for (const auto& [name, field] : BodyReals()) CheckFinite(name, d.*field, &problems);
  for (int i = 0; i < d.arm_count; ++i) {
    const ArmDescription& arm = d.arms[static_cast<size_t>(i)];
    CheckPositive(ArmKey(i, "length_m"), arm.length_m, "m", &problems);
    CheckPositive(ArmKey(i, "tip_mass_kg"), arm.tip_mass_kg, "kg", &problems);
    CheckPositive(ArmKey(i, "stiffness_n_m_rad"), arm.stiffness_n_m_rad, "N m/rad", &problems);
    CheckPositive(ArmKey(i, "thrust_coeff_n_s2_rad2"), arm.thrust_coeff_n_s2_rad2, "N s^2/rad^2", &problems);
    CheckPositive(ArmKey(i, "motor_time_constant_s"), arm.motor_time_constant_s, "s", &problems);
    for (const auto& [name, field] : ArmReals()) CheckFinite(ArmKey(i, name), arm.*field, &problems);
    if (arm.spin != 1 && arm.spin != -1) {
      problems.push_back(ArmKey(i, "spin") + ": " + Number(arm.spin) + " (allowed: 1 or -1)");
    }
  }
  return problems;
}

// The allocation must keep the controlled axes with margin.
void CheckAllocation(const VehicleDescription& d, std::vector<std::string>* problems) {
  const AllocationMargin margin = ControlledAxesMargin(d);
  if (margin.ratio >= kMinAllocationSingularRatio) return;
  std::ostringstream out;
  out << "allocation: the thrusts reach " << (margin.rows == 2 ? "F_z and the torque" : "F_x, F_z and the torque")
      << " with singular values [";
  for (Eigen::Index k = 0; k < margin.singular_values.size(); ++k) {
    out << (k == 0 ? "" : ", ") << margin.singular_values(k);
  }
  out << "] (torque row / mean arm length " << margin.mean_arm_length_m << " m), smallest / largest " << margin.ratio
      << " (allowed: >= " << kMinAllocationSingularRatio << "; the arms' angle_rad and thrust_angle_rad)";
  problems->push_back(out.str());
}

void CheckHover(const VehicleDescription& d, std::vector<std::string>* problems) {
  const HoverSolution hover = SolveHover(d);
  const std::string weight = " (total mass " + Number(d.TotalMass()) + " kg, gravity_m_s2 " + Number(d.gravity_m_s2) +
                             ", tip weights' moment " + Number(HoverWrench(d)(kWrenchTorque)) +
                             " N m, thrust_coeff_n_s2_rad2 ";
  for (int i = 0; i < d.arm_count; ++i) {
    const size_t k = static_cast<size_t>(i);
    const std::string c_t = Number(d.arms[k].thrust_coeff_n_s2_rad2) + ")";
    if (!(hover.thrust_n[k] > 0.0)) {
      problems->push_back("hover: rotor " + Number(i + 1) + " would need thrust " + Number(hover.thrust_n[k]) +
                          " N (allowed: > 0 N; a rotor only pushes)" + weight + c_t);
    } else if (hover.omega_rad_s[k] > d.omega_max_rad_s) {
      problems->push_back("hover: rotor " + Number(i + 1) + " needs " + Number(hover.thrust_n[k]) + " N, speed " +
                          Number(hover.omega_rad_s[k]) + " rad/s above omega_max_rad_s " + Number(d.omega_max_rad_s) +
                          " (allowed: hover speed <= omega_max_rad_s)" + weight + c_t);
    }
  }
}

void CheckGauges(const VehicleDescription& d, std::vector<std::string>* problems) {
  for (int i = 0; i < d.arm_count; ++i) {
    const ArmDescription& arm = d.arms[static_cast<size_t>(i)];
    const double lever_m = arm.ThrustLeverM();
    if (!arm.has_gauge || std::fabs(lever_m) >= kMinGaugeLeverFraction * arm.length_m) continue;
    problems->push_back(ArmKey(i, "has_gauge") + ": true on an arm whose thrust lever l = L cos(alpha - theta) = " +
                        Number(lever_m) + " m (length_m " + Number(arm.length_m) + ", angle_rad " +
                        Number(arm.angle_rad) + ", thrust_angle_rad " + Number(arm.thrust_angle_rad) +
                        "): the gauge cannot see the rotor's force (allowed: |l| >= " + Number(kMinGaugeLeverFraction) +
                        " x length_m, or has_gauge false)");
  }
}

}  // namespace

VehicleDescription BirotorDescription(const BirotorParams& p) {
  VehicleDescription d;
  d.name = "birotor";
  d.arm_count = kBirotorArmCount;
  d.body_mass_kg = p.body_mass_kg;
  d.body_inertia_kg_m2 = p.body_inertia_kg_m2;
  d.gravity_m_s2 = p.gravity_m_s2;
  d.omega_max_rad_s = p.omega_max_rad_s;
  d.turbulence_std = p.turbulence_std;
  d.turbulence_corr_time_s = p.turbulence_corr_time_s;
  d.gauge_offset_std_rad = p.gauge_offset_std_rad;
  d.gauge_drift_psd_rad2_s = p.gauge_drift_psd_rad2_s;
  for (int i = 0; i < kBirotorArmCount; ++i) {
    ArmDescription& arm = d.arms[static_cast<size_t>(i)];
    arm.angle_rad = (i == 0) ? kPi : 0.0;  // arm 1 along body -x, arm 2 along +x
    arm.length_m = p.arm_length_m;
    arm.thrust_angle_rad = 0.0;
    arm.spin = (i == 0) ? 1 : -1;
    arm.stiffness_n_m_rad = p.arm_stiffness_n_m_rad;
    arm.damping_n_m_s_rad = p.arm_damping_n_m_s_rad;
    arm.tip_mass_kg = p.tip_mass_kg;
    arm.thrust_coeff_n_s2_rad2 = p.thrust_coeff_n_s2_rad2;
    arm.motor_time_constant_s = p.motor_time_constant_s;
    arm.has_gauge = true;
    arm.gauge_scale = p.gauge_scale[i];
    arm.gauge_offset_rad = p.gauge_offset_rad[i];
  }
  return d;
}

bool ToBirotorParams(const VehicleDescription& d, BirotorParams* params, std::string* why) {
  if (d.arm_count != kBirotorArmCount) {
    *why = "arm_count is " + Number(d.arm_count) + "; BirotorParams holds a birotor of 2 arms";
    return false;
  }
  // Arm 1's scalars and both arms' gauges; the rest must then agree.
  BirotorParams p;
  const ArmDescription& arm = d.arms[0];
  p.body_mass_kg = d.body_mass_kg;
  p.tip_mass_kg = arm.tip_mass_kg;
  p.arm_length_m = arm.length_m;
  p.body_inertia_kg_m2 = d.body_inertia_kg_m2;
  p.arm_stiffness_n_m_rad = arm.stiffness_n_m_rad;
  p.arm_damping_n_m_s_rad = arm.damping_n_m_s_rad;
  p.gravity_m_s2 = d.gravity_m_s2;
  p.thrust_coeff_n_s2_rad2 = arm.thrust_coeff_n_s2_rad2;
  p.motor_time_constant_s = arm.motor_time_constant_s;
  p.omega_max_rad_s = d.omega_max_rad_s;
  p.turbulence_std = d.turbulence_std;
  p.turbulence_corr_time_s = d.turbulence_corr_time_s;
  for (int i = 0; i < kBirotorArmCount; ++i) {
    p.gauge_scale[i] = d.arms[static_cast<size_t>(i)].gauge_scale;
    p.gauge_offset_rad[i] = d.arms[static_cast<size_t>(i)].gauge_offset_rad;
  }
  p.gauge_offset_std_rad = d.gauge_offset_std_rad;
  p.gauge_drift_psd_rad2_s = d.gauge_drift_psd_rad2_s;
  VehicleDescription birotor = BirotorDescription(p);
  birotor.name = d.name;
  const std::string difference = FirstDifference(d, birotor);
  if (!difference.empty()) {
    *why =
        "not the birotor BirotorParams can hold (one value of each arm scalar for both arms, arm 1 at pi and "
        "arm 2 at 0 rad, thrust angles 0, spins +1 and -1, both gauges): " +
        difference + " (description vs birotor)";
    return false;
  }
  *params = p;
  why->clear();
  return true;
}

BirotorParams BirotorModelOf(const VehicleDescription& description) {
  BirotorParams params;
  std::string why;
  if (!ToBirotorParams(description, &params, &why)) {
    throw std::invalid_argument("vehicle '" + description.name + "' is not a birotor: " + why);
  }
  return params;
}

std::string FirstDifference(const VehicleDescription& a, const VehicleDescription& b) {
  if (a.name != b.name) return Differs("name", a.name, b.name);
  if (a.arm_count != b.arm_count) return Differs("arm_count", Number(a.arm_count), Number(b.arm_count));
  for (const auto& [name, field] : BodyReals()) {
    if (!Agree(name, a.*field, b.*field)) return Differs(name, Number(a.*field), Number(b.*field));
  }
  for (int i = 0; i < a.arm_count && i < kMaxArms; ++i) {
    const std::string difference =
        FirstArmDifference(i, a.arms[static_cast<size_t>(i)], b.arms[static_cast<size_t>(i)]);
    if (!difference.empty()) return difference;
  }
  return "";
}

AllocationMatrix WrenchAllocation(const VehicleDescription& d) {
  AllocationMatrix allocation(kWrenchSize, ValidArmCount(d) ? d.arm_count : 0);
  for (int i = 0; i < allocation.cols(); ++i) {
    const ArmDescription& arm = d.arms[static_cast<size_t>(i)];
    // u_i = [-sin theta_i, cos theta_i]; l_i = L_i (e_i x u_i) = L_i cos(alpha_i - theta_i).
    allocation(kWrenchFx, i) = -std::sin(arm.thrust_angle_rad);
    allocation(kWrenchFz, i) = std::cos(arm.thrust_angle_rad);
    allocation(kWrenchTorque, i) = arm.ThrustLeverM();
  }
  return allocation;
}

AllocationMargin ControlledAxesMargin(const VehicleDescription& d) {
  AllocationMargin margin;
  if (!ValidArmCount(d)) return margin;  // rows 0, ratio 0
  margin.rows = (d.arm_count == kBirotorArmCount) ? 2 : kWrenchSize;
  for (int i = 0; i < d.arm_count; ++i) margin.mean_arm_length_m += d.arms[static_cast<size_t>(i)].length_m;
  margin.mean_arm_length_m /= d.arm_count;
  AllocationMatrix normalized = WrenchAllocation(d);
  normalized.row(kWrenchTorque) /= margin.mean_arm_length_m;
  const Eigen::MatrixXd controlled = normalized.bottomRows(margin.rows);
  margin.singular_values = Eigen::JacobiSVD<Eigen::MatrixXd>(controlled).singularValues();
  const double largest = margin.singular_values(0);
  margin.ratio = largest > 0.0 ? margin.singular_values(margin.singular_values.size() - 1) / largest : 0.0;
  return margin;
}

Eigen::Vector3d HoverWrench(const VehicleDescription& d) {
  Eigen::Vector3d wrench = Eigen::Vector3d::Zero();
  if (!ValidArmCount(d)) return wrench;
  wrench(kWrenchFz) = d.gravity_m_s2 * d.TotalMass();
  // Tip i weighs m_p,i g at x = L_i cos alpha_i: its moment -m_p,i g x, which
  // the thrusts cancel. Summed term by term: the birotor's -m_p g L (cos pi
  // is -1 in double) and +m_p g L cancel exactly, its hover stays bitwise.
  for (int i = 0; i < d.arm_count; ++i) {
    const ArmDescription& arm = d.arms[static_cast<size_t>(i)];
    wrench(kWrenchTorque) += arm.tip_mass_kg * d.gravity_m_s2 * arm.length_m * std::cos(arm.angle_rad);
  }
  return wrench;
}

HoverSolution SolveHover(const VehicleDescription& d) {
  if (!ValidArmCount(d)) return HoverSolution();
  const AllocationMatrix allocation = WrenchAllocation(d);
  const int rows = (d.arm_count == kBirotorArmCount) ? 2 : kWrenchSize;
  const Eigen::Vector3d wrench = HoverWrench(d);
  // The complete orthogonal decomposition gives the least-norm solution of
  // an underdetermined system, and the exact one of a square regular one.
  const Eigen::MatrixXd a = allocation.bottomRows(rows);
  const Eigen::VectorXd thrust = a.completeOrthogonalDecomposition().solve(wrench.tail(rows));
  HoverSolution hover;
  for (int i = 0; i < d.arm_count; ++i) {
    const size_t k = static_cast<size_t>(i);
    hover.thrust_n[k] = thrust(i);
    hover.omega_rad_s[k] = thrust(i) > 0.0 ? std::sqrt(thrust(i) / d.arms[k].thrust_coeff_n_s2_rad2) : 0.0;
  }
  return hover;
}

std::vector<std::string> PlausibilityProblems(const VehicleDescription& d) {
  std::vector<std::string> problems = FieldProblems(d);
  if (!problems.empty()) return problems;
  CheckAllocation(d, &problems);
  if (problems.empty()) CheckHover(d, &problems);  // hover needs the full rank
  CheckGauges(d, &problems);
  return problems;
}

}  // namespace birotor
