// The shape of a planar vehicle with N elastic arms: one type every room can
// use to ask how many rotors there are and where they push. Plain data, SI
// units. The birotor of the reference file is the case N = 2 (BirotorDescription).
//
// Frames (docs/vehicle-description.md): body x right, body z up, angles
// positive in the sense of the tilt phi (turning body +x towards +z). Arm i is
// hinged at the body centre through a torsional spring; undeflected it points
// along e_i = [cos alpha_i, sin alpha_i] (body frame). Its tip carries the
// lumped mass m_p,i and a rotor whose thrust, undeflected, points along
// u_i = [-sin theta_i, cos theta_i] (theta_i = 0: body up). A deflection b_i
// turns both e_i and u_i by b_i, so in the world frame
//   p_i = p + L_i R(phi + b_i) e_i,   n_i = R(phi + b_i) u_i.
// The thrust's moment about the hinge, per newton, is the lever
//   l_i = L_i (e_i x u_i) = L_i cos(alpha_i - theta_i)   [m],
// which is what a gauge on arm i can see of f_i (l_i = 0: the gauge sees nothing).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "model/birotor_params.h"

namespace birotor {

// The most arms a description may have (the wire's per-rotor fault bits).
inline constexpr int kMaxArms = 6;
// The reference birotor's arm count (the fixed-size birotor messages).
inline constexpr int kBirotorArmCount = 2;

// One elastic arm, its hinge, its tip mass, its rotor and its gauge.
struct ArmDescription {
  double angle_rad = 0.0;                  // alpha_i: undeflected arm direction in the body frame [rad]
  double length_m = 0.25;                  // L_i: hinge (body centre) to rotor axis [m]
  double thrust_angle_rad = 0.0;           // theta_i: thrust direction from body up, undeflected [rad]
  int spin = 1;                            // +1 counter-clockwise seen from the thrust side, -1 clockwise
  double stiffness_n_m_rad = 2628.0;       // k_i: hinge torsional stiffness [N m/rad]
  double damping_n_m_s_rad = 0.25;         // d_i: hinge viscous damping [N m s/rad]
  double tip_mass_kg = 0.28812;            // m_p,i: motor, propeller and arm lumped at the tip [kg]
  double thrust_coeff_n_s2_rad2 = 4.6e-5;  // c_T,i: nominal map f = c_T omega^2 [N s^2/rad^2]
  double motor_time_constant_s = 0.035;    // tau_m,i: first-order speed response [s]
  bool has_gauge = true;                   // a strain gauge measures b_i
  double gauge_scale = 1.0;                // s_i: the gauge reads s_i b_i + o_i [1]
  double gauge_offset_rad = 0.0;           // o_i at power-up, if known [rad]

  // l_i = L_i cos(alpha_i - theta_i): hinge moment per newton of thrust [m].
  double ThrustLeverM() const { return length_m * std::cos(angle_rad - thrust_angle_rad); }
};

// A planar body with arm_count elastic arms.
struct VehicleDescription {
  std::string name = "birotor";
  int arm_count = kBirotorArmCount;
  std::array<ArmDescription, kMaxArms> arms{};  // arms[0 .. arm_count)
  double body_mass_kg = 4.0;                    // m: body without the tip masses [kg]
  double body_inertia_kg_m2 = 0.05;             // J: body about its centre (y axis) [kg m^2]
  double gravity_m_s2 = 9.81;                   // g [m/s^2]
  double omega_max_rad_s = 1200.0;              // every rotor's command clamp [0, omega_max] [rad/s]
  double turbulence_std = 0.01;                 // eta: relative thrust turbulence, std [1]
  double turbulence_corr_time_s = 0.1;          // eta: Gauss-Markov correlation time [s]
  double gauge_offset_std_rad = 5.0e-5;         // how well each o_i is known before a tare [rad]
  double gauge_drift_psd_rad2_s = 1.0e-10;      // random walk of each o_i in flight [rad^2/s]

  // m + sum_i m_p,i [kg].
  double TotalMass() const {
    double total = body_mass_kg;
    for (int i = 0; i < arm_count; ++i) total += arms[static_cast<size_t>(i)].tip_mass_kg;
    return total;
  }
  int GaugeCount() const {
    int n = 0;
    for (int i = 0; i < arm_count; ++i) n += arms[static_cast<size_t>(i)].has_gauge ? 1 : 0;
    return n;
  }
};

// ---------------------------------------------------------------------------
// Helpers on a description (model/vehicle_description.cc): the birotor both
// ways, the thrust-to-wrench allocation, hover, and whether it can fly.

// The body wrench at the centre, body frame: F_x, F_z [N] and the torque
// about the centre [N m], positive in the sense of phi.
enum WrenchRow : int { kWrenchFx = 0, kWrenchFz = 1, kWrenchTorque = 2 };
inline constexpr int kWrenchSize = 3;

// 3 x N, at most 3 x kMaxArms (no heap allocation).
using AllocationMatrix = Eigen::Matrix<double, kWrenchSize, Eigen::Dynamic, Eigen::ColMajor, kWrenchSize, kMaxArms>;

// The plausibility thresholds (docs/vehicle-description.md, "Plausibility").
// Smallest over largest singular value of the allocation on the axes the
// controller needs, with the torque row divided by the mean arm length (so
// the ratio is a property of the shape, not of the size): below this the
// vehicle is too close to losing an axis. The birotor has 1, the trirotor of
// config/vehicles/trirotor.yaml 0.563.
inline constexpr double kMinAllocationSingularRatio = 0.1;
// A gauge on arm i needs |l_i| >= this x L_i (|cos(alpha_i - theta_i)| >= 0.1:
// the thrust at least 5.7 deg off the arm's axis); below, f_i barely bends it.
inline constexpr double kMinGaugeLeverFraction = 0.1;
// FirstDifference: relative tolerance on every real field (angles: absolute
// [rad], modulo 2 pi), so that a file written in degrees equals the radians.
inline constexpr double kDescriptionTolerance = 1e-12;

// The reference birotor as a description: arm 1 at alpha = pi, arm 2 at
// alpha = 0, both theta = 0, spins +1 and -1 (counter-rotating; no effect in
// the plane), every arm field from the shared scalars, gauge scale and offset
// per arm, has_gauge true.
VehicleDescription BirotorDescription(const BirotorParams& params);

// The reverse, for a description that is a birotor: false, with *why naming
// the first field that BirotorParams cannot hold (arm_count, an arm's
// geometry, has_gauge false, spin, or arms that differ in a shared scalar).
bool ToBirotorParams(const VehicleDescription& description, BirotorParams* params, std::string* why);

// The birotor model's parameters of a description that is a birotor, for a
// room's constructor (not the per-sample path). Throws std::invalid_argument
// with ToBirotorParams's reason otherwise; loaders refuse such a file first
// (RequireBirotor in params/vehicle_description_yaml.h), naming file and key.
BirotorParams BirotorModelOf(const VehicleDescription& description);

// "" when a and b agree (arms[0 .. arm_count) only; kDescriptionTolerance),
// else the first differing field and both values, e.g.
// "arms[1].stiffness_n_m_rad: 3000 vs 2628".
std::string FirstDifference(const VehicleDescription& a, const VehicleDescription& b);

// WrenchAllocation, ControlledAxesMargin, HoverWrench and SolveHover need
// arm_count in [2, kMaxArms]; outside it they return an empty matrix, rows 0
// and zeros.
//
// Column i maps thrust f_i [N] to the body wrench at zero deflection:
//   [F_x; F_z] += f_i u_i,  torque += f_i l_i,  l_i = L_i (e_i x u_i).
AllocationMatrix WrenchAllocation(const VehicleDescription& description);

// The allocation rows the controller needs (N = 2: F_z and torque, the
// birotor tilts for F_x; N >= 3: all three), torque row divided by the mean
// arm length, and their singular values, largest first.
struct AllocationMargin {
  int rows = 0;                     // 2 or 3
  double mean_arm_length_m = 0.0;   // the torque row's divisor [m]
  Eigen::VectorXd singular_values;  // [N per N of thrust], largest first
  double ratio = 0.0;               // smallest / largest [1]
};
AllocationMargin ControlledAxesMargin(const VehicleDescription& description);

// The wrench [F_x, F_z, tau] (rows kWrenchFx, kWrenchFz, kWrenchTorque) the
// thrusts must give to hold the level, undeflected vehicle at rest: minus the
// gravity wrench of the body (at the centre) and of every tip mass (at
// L_i e_i), torque tau = x F_z - z F_x about the centre:
//   w_hover = [0,  g (m + sum_i m_p,i),  sum_i m_p,i g L_i cos alpha_i].
// The last row is the tip weights' moment, which the thrusts must cancel:
// 0 on the birotor (cos pi + cos 0 = 0), 0.293 N m on the trirotor of
// config/vehicles/trirotor.yaml. Zeros outside arm_count [2, kMaxArms].
Eigen::Vector3d HoverWrench(const VehicleDescription& description);

// Thrusts and speeds that hold the level, undeflected vehicle at rest, the
// one rigid-hover allocation of the project (the N-arm hover of
// model/multi_arm_linearization.h starts from it). The body wrench rows
// [F_x, F_z, tau] = A f (WrenchAllocation) cancel the gravity wrench of the
// body and every tip mass at zero deflection (HoverWrench):
//   A f = [0,  g (m + sum_i m_p,i),  sum_i m_p,i g L_i cos alpha_i].
// N = 2: the F_z and torque rows solved (F_x is whatever the thrust
// directions give; 0 for the birotor); N >= 3: the least-norm solution of all
// three rows. omega_i = sqrt(f_i / c_T,i) (0 where f_i <= 0). The exact hover
// adds the arms' static deflection.
struct HoverSolution {
  std::array<double, kMaxArms> thrust_n{};     // f_i [N]
  std::array<double, kMaxArms> omega_rad_s{};  // [rad/s]
};
HoverSolution SolveHover(const VehicleDescription& description);

// Every reason the description cannot fly, one sentence each with the
// numbers, the key and the allowed range; empty when it can. Checked:
// arm_count in [2, kMaxArms]; masses, inertia, lengths, stiffness, c_T,
// tau_m and omega_max positive and finite, every other number finite;
// spin +1 or -1; the allocation margin (ratio >= kMinAllocationSingularRatio);
// SolveHover's thrusts > 0 and speeds <= omega_max; a gauge only where
// |l_i| >= kMinGaugeLeverFraction L_i.
std::vector<std::string> PlausibilityProblems(const VehicleDescription& description);

}  // namespace birotor
