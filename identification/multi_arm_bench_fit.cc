// IdentifyMultiArmBench (multi_arm_bench_fit.h): the count check, every
// arm's clamped-arm fit (multi_arm_arm_fit.cc) and every rotor's c_T and
// tau_m by the birotor's own fits on that rotor's data alone.
#include "identification/multi_arm_bench_fit.h"

#include <cmath>
#include <limits>
#include <string>

#include "identification/identify.h"
#include "identification/multi_arm_fit_parts.h"

namespace birotor {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <class Sample>
int CountOf(const Sample& s) {
  if constexpr (std::is_same_v<Sample, MultiArmStrainSample>) {
    return s.n_arms;
  } else {
    return s.n_rotors;
  }
}

template <class Sample>
std::string StreamMismatch(const std::vector<Sample>& samples, const char* channel, int arm_count) {
  for (const Sample& s : samples) {
    if (CountOf(s) != arm_count) {
      return std::string(channel) + " sample at utime " + std::to_string(s.utime) + " has " +
             std::to_string(CountOf(s)) + " entries, the description " + std::to_string(arm_count);
    }
  }
  return "";
}

// The birotor's estimate of `key` in result (NaN, not determined, when absent).
ParameterEstimate Take(const IdentificationResult& result, const std::string& key, const std::string& symbol) {
  for (const ParameterEstimate& e : result.estimates) {
    if (e.key == key) {
      ParameterEstimate out = e;
      out.symbol = symbol;
      return out;
    }
  }
  return ParameterEstimate::Named(key, symbol);
}

// One arm: data, start, scan, build, solve; false (with *error) without
// enough strain/load-cell pairs.
bool FitArm(const std::vector<MultiArmBenchLog>& logs, const VehicleDescription& base, int arm,
            const IdentificationOptions& options, ArmEstimates* out, std::string* error) {
  std::vector<double> map_b, map_f;
  const std::vector<ArmData> data = CollectMultiArmData(logs, arm, &map_b, &map_f);
  const std::vector<ArmWindow> windows = ArmWindows(data, options);
  if (map_f.size() < 20 || windows.empty()) {
    *error = "k, d, m_p: no STRAIN_N samples paired with LOADCELL_N samples";
    return false;
  }
  const ArmFitStart start = StartArmFit(data, windows, map_b, map_f, base, arm, options);
  BenchArmProblem fit;
  fit.theta = start.theta;
  BuildArmProblem(data, windows, start, options, &fit);
  SolveArmFit(start, options, &fit, out);
  return true;
}

// One rotor: c_T (load cells against telemetry) and tau_m (telemetry against
// commands), the birotor's fits on this rotor alone.
void FitRotor(const std::vector<MultiArmBenchLog>& logs, const VehicleDescription& base, int rotor,
              const IdentificationOptions& options, ArmEstimates* out, std::vector<std::string>* errors) {
  const ArmDescription& a = base.arms[static_cast<size_t>(rotor)];
  BirotorParams rotor_base;
  rotor_base.thrust_coeff_n_s2_rad2 = a.thrust_coeff_n_s2_rad2;
  rotor_base.motor_time_constant_s = a.motor_time_constant_s;
  rotor_base.omega_max_rad_s = base.omega_max_rad_s;
  rotor_base.turbulence_std = base.turbulence_std;
  const std::vector<SensorLog> rotor_logs = RotorAsBirotorLogs(logs, rotor);
  IdentificationResult result;
  IdentifyBenchThrust(rotor_logs, rotor_base, options, &result);
  IdentifyMotorTimeConstant(rotor_logs, rotor_base, options, &result);
  out->thrust_coeff = Take(result, "thrust_coeff_n_s2_rad2", "c_T," + std::to_string(rotor + 1));
  out->motor_time_constant = Take(result, "motor_time_constant_s", "tau_m," + std::to_string(rotor + 1));
  for (const std::string& e : result.errors) errors->push_back("rotor " + std::to_string(rotor + 1) + ": " + e);
}

void Store(const ArmEstimates& e, ArmDescription* arm) {
  if (e.stiffness.determined) arm->stiffness_n_m_rad = e.stiffness.value;
  if (e.damping.determined) arm->damping_n_m_s_rad = e.damping.value;
  if (e.tip_mass.determined) arm->tip_mass_kg = e.tip_mass.value;
  if (e.gauge_offset.determined) arm->gauge_offset_rad = e.gauge_offset.value;
  if (e.thrust_coeff.determined) arm->thrust_coeff_n_s2_rad2 = e.thrust_coeff.value;
  if (e.motor_time_constant.determined) arm->motor_time_constant_s = e.motor_time_constant.value;
}

}  // namespace

std::string MultiArmLogMismatch(const MultiArmBenchLog& log, const VehicleDescription& base) {
  const int n = base.arm_count;
  if (log.has_vehicle && log.vehicle.arm_count != n) {
    return log.source + ": VEHICLE has " + std::to_string(log.vehicle.arm_count) + " arms, the description " +
           std::to_string(n);
  }
  for (const std::string& why : {StreamMismatch(log.strain, "STRAIN_N", n), StreamMismatch(log.motor, "MOTOR_N", n),
                                 StreamMismatch(log.loadcell, "LOADCELL_N", n)}) {
    if (!why.empty()) return log.source + ": " + why;
  }
  return "";
}

std::vector<SensorLog> RotorAsBirotorLogs(const std::vector<MultiArmBenchLog>& logs, int rotor) {
  const size_t i = static_cast<size_t>(rotor);
  std::vector<SensorLog> out;
  for (const MultiArmBenchLog& log : logs) {
    SensorLog s;
    s.source = log.source;
    for (const MultiArmMotorSample& m : log.motor) {
      MotorSample b;
      b.utime = m.utime;
      b.seq = m.seq;
      b.omega_cmd_rad_s[0] = m.omega_cmd_rad_s[i];
      b.omega_meas_rad_s[0] = m.omega_meas_rad_s[i];
      b.omega_cmd_rad_s[1] = b.omega_meas_rad_s[1] = kNaN;
      s.motor.push_back(b);
    }
    for (const MultiArmLoadCellSample& c : log.loadcell) {
      LoadCellSample b;
      b.utime = c.utime;
      b.seq = c.seq;
      b.force_n[0] = c.force_n[i];
      b.force_n[1] = kNaN;
      s.loadcell.push_back(b);
    }
    out.push_back(std::move(s));
  }
  return out;
}

MultiArmIdentificationResult IdentifyMultiArmBench(const std::vector<MultiArmBenchLog>& logs,
                                                   const VehicleDescription& base,
                                                   const IdentificationOptions& options) {
  MultiArmIdentificationResult result;
  result.vehicle = base;
  for (const MultiArmBenchLog& log : logs) {
    const std::string why = MultiArmLogMismatch(log, base);
    if (!why.empty()) result.errors.push_back(why);
  }
  if (logs.empty()) result.errors.push_back("no log");
  if (options.calibration.TipMassWeighed() || options.calibration.gauge_scale_std > 0.0) {
    result.errors.push_back("a calibration fact (weighed tip mass, gauge scale sigma) is not supported for N arms");
  }
  if (!result.errors.empty()) return result;
  result.arms.resize(static_cast<size_t>(base.arm_count));
  for (int arm = 0; arm < base.arm_count; ++arm) {
    ArmEstimates& e = result.arms[static_cast<size_t>(arm)];
    const std::string n = std::to_string(arm + 1);
    e.stiffness = ParameterEstimate::Named("stiffness_n_m_rad", "k_" + n);
    e.damping = ParameterEstimate::Named("damping_n_m_s_rad", "d_" + n);
    e.tip_mass = ParameterEstimate::Named("tip_mass_kg", "m_p," + n);
    e.gauge_offset = ParameterEstimate::Named("gauge_offset_rad", "o_" + n);
    std::string error;
    if (!base.arms[static_cast<size_t>(arm)].has_gauge) {
      result.errors.push_back("arm " + n + ": no gauge, k, d, m_p not identified on the bench");
    } else if (!FitArm(logs, base, arm, options, &e, &error)) {
      result.errors.push_back("arm " + n + ": " + error);
    } else {
      if (!e.stiffness.determined) result.errors.push_back("arm " + n + ": k not determined by the bench strain data");
      if (!e.gauge_offset.determined) result.errors.push_back("arm " + n + ": gauge offset not determined");
    }
    FitRotor(logs, base, arm, options, &e, &result.errors);
    Store(e, &result.vehicle.arms[static_cast<size_t>(arm)]);
  }
  result.ok = result.errors.empty();
  return result;
}

}  // namespace birotor
