#include "controller/multi_arm_flare.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "controller/wrench_allocation.h"

namespace birotor {
namespace {

// A vertex may miss a row by this share of the largest term of the row (round-off) [1].
constexpr double kRowTolerance = 1e-9;

// The flare's linear programme: max c f with 0 <= a f <= a_max, (holds
// lateral) e f = 0 and 0 <= f_i <= u_i (N rotors).
struct FlareProgramme {
  int n = 0;
  double c[kMaxArms] = {};  // world vertical force per N [1]
  double a[kMaxArms] = {};  // pitch torque towards the strong side per N [m]
  double e[kMaxArms] = {};  // body F_x per N [1]
  double u[kMaxArms] = {};  // [N]
  double a_max = 0.0;       // [N m]
  bool holds_lateral = false;
  double torque_tolerance = 0.0;   // [N m]
  double lateral_tolerance = 0.0;  // [N]
};

// The rows' values of f.
double Dot(const double* row, const double* f, int n) {
  double total = 0.0;
  for (int i = 0; i < n; ++i) total += row[i] * f[i];
  return total;
}

// f is feasible: within the bounds (kRowTolerance of u_i, then clamped) and both rows.
bool Feasible(const FlareProgramme& p, double* f) {
  for (int i = 0; i < p.n; ++i) {
    const double slack_n = kRowTolerance * std::max(p.u[i], 1.0);
    if (!(f[i] >= -slack_n && f[i] <= p.u[i] + slack_n)) return false;
    f[i] = std::clamp(f[i], 0.0, p.u[i]);
  }
  const double torque = Dot(p.a, f, p.n);
  if (torque < -p.torque_tolerance || torque > p.a_max + p.torque_tolerance) return false;
  return !p.holds_lateral || std::fabs(Dot(p.e, f, p.n)) <= p.lateral_tolerance;
}

// The candidate vertices with every thrust at 0 or u_i (bit i of mask) but
// rotors j and k (-1: none): j meets the torque row's bound or the lateral
// row; j and k (lateral held) meet both. The best feasible one goes to *f
// when its vertical force beats *best.
void TryVertices(const FlareProgramme& p, int j, int k, unsigned mask, double* best, double (&f)[kMaxArms]) {
  double x[kMaxArms] = {};
  for (int i = 0; i < p.n; ++i) x[i] = (i != j && i != k && (mask >> i & 1u) != 0) ? p.u[i] : 0.0;
  const double torque_rest = Dot(p.a, x, p.n);
  const double lateral_rest = Dot(p.e, x, p.n);
  const auto keep = [&]() {
    if (!Feasible(p, x)) return;
    const double value = Dot(p.c, x, p.n);
    if (!(value > *best)) return;
    *best = value;
    std::copy(x, x + kMaxArms, f);
  };
  if (j < 0) {
    keep();
    return;
  }
  if (k < 0) {
    for (double bound : {0.0, p.a_max}) {
      if (p.a[j] == 0.0) break;
      x[j] = (bound - torque_rest) / p.a[j];
      keep();
    }
    if (p.holds_lateral && p.e[j] != 0.0) {
      x[j] = -lateral_rest / p.e[j];
      keep();
    }
    return;
  }
  // [a_j a_k; e_j e_k] [x_j; x_k] = [bound - torque_rest; -lateral_rest].
  const double det = p.a[j] * p.e[k] - p.a[k] * p.e[j];
  if (det == 0.0) return;
  for (double bound : {0.0, p.a_max}) {
    const double torque = bound - torque_rest;
    x[j] = (torque * p.e[k] + p.a[k] * lateral_rest) / det;
    x[k] = (-p.a[j] * lateral_rest - p.e[j] * torque) / det;
    keep();
  }
}

}  // namespace

double FlareTiltBudgetFor(const VehicleDescription& vehicle, const EfficiencyParams& params) {
  const bool fully_actuated = MultiArmControlModeFor(vehicle) == MultiArmControlMode::kFullyActuated;
  return fully_actuated ? params.flare_tilt_fully_actuated_rad : params.flare_tilt_rad;
}

MultiArmFlareLimits FlareGeometryOf(const VehicleDescription& vehicle, double tilt_budget_rad) {
  MultiArmFlareLimits limits;
  limits.tilt_budget_rad = tilt_budget_rad;
  limits.rotor_count = vehicle.arm_count;
  limits.holds_lateral = MultiArmControlModeFor(vehicle) == MultiArmControlMode::kFullyActuated;
  limits.pitch_inertia_kg_m2 = vehicle.body_inertia_kg_m2;
  const AllocationMatrix w = WrenchAllocation(vehicle);
  for (int i = 0; i < vehicle.arm_count && i < w.cols(); ++i) {
    const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
    limits.pitch_inertia_kg_m2 += arm.tip_mass_kg * arm.length_m * arm.length_m;
    limits.min_time_to_go_s = std::max(limits.min_time_to_go_s, arm.motor_time_constant_s);
    limits.lateral[i] = w(kWrenchFx, i);
    limits.vertical[i] = w(kWrenchFz, i);
    limits.torque_m[i] = w(kWrenchTorque, i);
  }
  return limits;
}

MultiArmFlareForces MultiArmFlareForcesFor(const FlareState& state, const MultiArmFlareLimits& limits) {
  MultiArmFlareForces out;
  FlareProgramme p;
  p.n = std::clamp(limits.rotor_count, 0, kMaxArms);
  p.holds_lateral = limits.holds_lateral;
  double strong_torque_n_m = 0.0;  // every rotor at its maximum
  double largest_torque_n_m = 1.0;
  double largest_lateral_n = 1.0;
  for (int i = 0; i < p.n; ++i) {
    p.u[i] = std::isfinite(limits.max_force_n[i]) ? std::max(limits.max_force_n[i], 0.0) : 0.0;
    strong_torque_n_m += limits.torque_m[i] * p.u[i];
    largest_torque_n_m = std::max(largest_torque_n_m, std::fabs(limits.torque_m[i]) * p.u[i]);
    largest_lateral_n = std::max(largest_lateral_n, std::fabs(limits.lateral[i]) * p.u[i]);
  }
  const double sign = strong_torque_n_m < 0.0 ? -1.0 : 1.0;
  // A non-finite height or sink counts as on the ground: t_go the motor lag.
  const double sink_m_s = std::isfinite(state.sink_rate_m_s) ? std::max(state.sink_rate_m_s, 1e-6) : 1e-6;
  const double height_m = std::isfinite(state.height_m) ? std::max(state.height_m, 0.0) : 0.0;
  out.time_to_go_s = std::max(height_m / sink_m_s, limits.min_time_to_go_s);
  const double t = std::max(out.time_to_go_s, 1e-6);
  const double tilt_left_rad = limits.tilt_budget_rad - sign * (state.tilt_rad + state.pitch_rate_rad_s * t);
  const double torque_want_n_m = 2.0 * limits.pitch_inertia_kg_m2 * tilt_left_rad / (t * t);
  // A non-finite state asks for no torque (the caller's guard sees the law's output).
  p.a_max = std::isfinite(torque_want_n_m) ? std::max(torque_want_n_m, 0.0) : 0.0;
  p.torque_tolerance = kRowTolerance * largest_torque_n_m;
  p.lateral_tolerance = kRowTolerance * largest_lateral_n;
  const double phi_rad = std::isfinite(state.tilt_rad) ? state.tilt_rad : 0.0;
  for (int i = 0; i < p.n; ++i) {
    // World z of the body force [F_x, F_z]: sin(phi) F_x + cos(phi) F_z.
    p.c[i] = std::sin(phi_rad) * limits.lateral[i] + std::cos(phi_rad) * limits.vertical[i];
    p.a[i] = sign * limits.torque_m[i];
    p.e[i] = limits.lateral[i];
  }
  // f = 0 is feasible: the best is at least its 0.
  double best = -std::numeric_limits<double>::infinity();
  for (int j = -1; j < p.n; ++j) {
    for (int k = p.holds_lateral && j >= 0 ? j + 1 : p.n; k <= p.n; ++k) {
      const int second = k < p.n ? k : -1;
      for (unsigned mask = 0; mask < (1u << p.n); ++mask) {
        if ((j >= 0 && (mask >> j & 1u) != 0) || (second >= 0 && (mask >> second & 1u) != 0)) continue;
        TryVertices(p, j, second, mask, &best, out.force_n);
      }
    }
  }
  for (int i = 0; i < p.n; ++i) {
    out.torque_n_m += limits.torque_m[i] * out.force_n[i];
    out.vertical_n += p.c[i] * out.force_n[i];
  }
  return out;
}

}  // namespace birotor
