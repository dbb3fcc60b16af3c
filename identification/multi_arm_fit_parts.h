// The stages of the N-arm bench fit (multi_arm_bench_fit.h), each callable
// on its own by a test: one arm's clamped-arm data, start and scan, build,
// solve with sigmas (multi_arm_arm_fit.cc); one rotor's data as a birotor
// SensorLog for the birotor's c_T and tau_m fits (multi_arm_bench_fit.cc).
#pragma once

#include <vector>

#include "identification/bench_fit.h"
#include "identification/multi_arm_bench_fit.h"
#include "model/arm_dynamics.h"

namespace birotor {

// Strain samples of arm `arm` of every log with that rotor's load-cell force
// at the same time (ArmData with the gauge slot 0); the valid pairs also go
// to map_b, map_f (the static line's data).
std::vector<ArmData> CollectMultiArmData(const std::vector<MultiArmBenchLog>& logs, int arm, std::vector<double>* map_b,
                                         std::vector<double>* map_f);

// Where the solve of one arm starts: its hinge, its static line, the ratio
// units (the description's k, d, m_p) and theta after the frequency scan.
struct ArmFitStart {
  ClampedArmGeometry geometry;
  StaticLine line;
  ClampedArmWindowResidual::Scales scales{};
  BenchTheta theta{};
};
ArmFitStart StartArmFit(const std::vector<ArmData>& data, const std::vector<ArmWindow>& windows,
                        const std::vector<double>& map_b, const std::vector<double>& map_f,
                        const VehicleDescription& base, int arm, const IdentificationOptions& options);
void BuildArmProblem(const std::vector<ArmData>& data, const std::vector<ArmWindow>& windows, const ArmFitStart& start,
                     const IdentificationOptions& options, BenchArmProblem* fit);
void SolveArmFit(const ArmFitStart& start, const IdentificationOptions& options, BenchArmProblem* fit,
                 ArmEstimates* out);

// Rotor `rotor` of every log as a birotor SensorLog: its MOTOR_N and
// LOADCELL_N entries in slot 0, NaN in slot 1 (which every birotor fit skips).
std::vector<SensorLog> RotorAsBirotorLogs(const std::vector<MultiArmBenchLog>& logs, int rotor);

}  // namespace birotor
