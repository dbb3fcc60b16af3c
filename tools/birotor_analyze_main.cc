// birotor-analyze: the model analysis of thesis ch. 3-4 and 6 for a parameter
// file: hover equilibrium, linearized A and B, arm modes, and observability /
// controllability tables that are numerically sound for this stiff system.
// With --vehicle, the N-arm analysis of a vehicle description instead
// (model/vehicle_analysis.h, printed as docs/multi-arm-model.md shows it).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "model/equilibrium.h"
#include "model/linearization.h"
#include "model/observability.h"
#include "model/parameter_observability.h"
#include "model/vehicle_analysis.h"
#include "params/birotor_params_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "program/config_files.h"
#include "program/program_options.h"
#include "tools/vehicle_analysis_text.h"

namespace birotor {
namespace {

std::vector<std::string> SplitComma(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

void PrintMatrix(const char* title, const Eigen::MatrixXd& m, const std::vector<std::string>& row_names) {
  std::printf("\n%s\n", title);
  // Round-off below 1e-12 of the largest entry prints as 0.
  const double floor = 1e-12 * m.cwiseAbs().maxCoeff();
  for (int i = 0; i < m.rows(); ++i) {
    std::printf("  %-8s", row_names[i].c_str());
    for (int j = 0; j < m.cols(); ++j) std::printf(" %12.5g", std::abs(m(i, j)) < floor ? 0.0 : m(i, j));
    std::printf("\n");
  }
}

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
  return out.empty() ? "-" : out;
}

// Issue 27: the slow parameters in-flight data determine, with and without the accelerometer.
void PrintParameterObservability(const BirotorParams& params) {
  using M = ParameterMeasurement;
  const struct {
    const char* name;
    std::vector<M> measured;
  } sets[] = {{"strain, telemetry, gyro", {M::kStrain, M::kTelemetry, M::kGyro}},
              {"strain, telemetry, gyro, accelerometer", {M::kStrain, M::kTelemetry, M::kGyro, M::kAccelerometer}}};
  std::printf(
      "\nSlow parameters as constant states (24 states: the 10 mechanical ones, omega_i, thrust scales mu_i,\n"
      "gauge offsets o_i, and relative deviations of k1, k2, m, m_p, c_T, tau_m, s1, s2; hover, held commands)\n\n");
  std::printf(
      "| measured | rank | single axes determined | determined combinations (of 12) | sigma_rank / sigma_max |\n");
  std::printf("|---|---|---|---|---|\n");
  for (const auto& set : sets) {
    const ParameterObservability r = AnalyzeParameterObservability(params, set.measured);
    std::string combinations = std::to_string(r.determined) + ": ";
    for (const std::string& c : r.determined_combinations) combinations += "[" + c + "] ";
    std::printf("| %s | %d / %d | %s | %s | %.3g |\n", set.name, r.report.rank, r.report.state_size,
                Join(r.observable_parameters).c_str(), combinations.c_str(),
                r.report.singular_values(r.report.rank - 1) / r.report.singular_values(0));
  }
  std::printf(
      "At one hover point with held commands only steady effects count: tau_m (it scales omega - command = 0)\n"
      "is never determined there, and the arm-mode effects of m_p need manoeuvres (docs/mismatch.md).\n");
}

// --vehicle FILE [--without-gauge I ...]: the N-arm analysis of one description.
int RunVehicleAnalysis(const std::string& vehicle_file, const std::vector<int>& without_gauge) {
  VehicleDescription loaded;
  try {
    loaded = LoadVehicleDescription(vehicle_file);
  } catch (const ParamError& e) {
    return ReportError(e.what());
  }
  VehicleDescription vehicle;
  std::string why;
  if (!VehicleWithoutGauges(loaded, without_gauge, &vehicle, &why)) {
    return ReportError("--without-gauge: " + why + " in " + vehicle_file, kExitUsage);
  }
  std::printf("Vehicle file: %s\n\n%s", vehicle_file.c_str(),
              VehicleAnalysisText(vehicle, AnalyzeVehicle(vehicle)).c_str());
  return 0;
}

// Without --vehicle: the birotor analysis of --params (BirotorParams, the thesis's sets).
int RunBirotorAnalysis(const std::string& params_file, std::vector<std::string> measure_sets, bool thesis_coordinates) {
  BirotorParams params;
  try {
    params = LoadBirotorParams(params_file);
  } catch (const ParamError& e) {
    return ReportError(e.what());
  }
  if (measure_sets.empty()) measure_sets = {"b1,b2", "x,z", "x,z,phi,b1,b2,x_dot,z_dot,phi_dot,b1_dot,b2_dot"};

  // Every --measure set is checked before anything is printed.
  const std::vector<std::string> names = AugmentedStateNames();
  std::vector<Eigen::MatrixXd> selections(measure_sets.size());
  for (size_t i = 0; i < measure_sets.size(); ++i) {
    std::string unknown;
    if (!SelectionMatrix(names, SplitComma(measure_sets[i]), &selections[i], &unknown)) {
      return ReportError("--measure: unknown state '" + unknown + "' (allowed: " + Join(names) + ")", kExitUsage);
    }
  }

  const Equilibrium eq = SolveHoverEquilibrium(params);
  if (!eq.converged) {
    return ReportError("no hover equilibrium found (residual " + std::to_string(eq.residual) + ")");
  }
  std::printf("Parameter file: %s\n\nHover equilibrium (phi = 0)\n", params_file.c_str());
  std::printf("  f1 = %.6f N, f2 = %.6f N   (g (m + 2 m_p) / 2 = %.6f N)\n", eq.force_n[0], eq.force_n[1],
              params.HoverForceN());
  std::printf("  b1 = %.7f rad, b2 = %.7f rad\n", eq.deflection_rad[0], eq.deflection_rad[1]);
  std::printf("  omega1 = omega2 = %.3f rad/s   (c_T = %g N s^2/rad^2)\n", eq.omega_rad_s[0],
              params.thrust_coeff_n_s2_rad2);

  LinearModel lin = LinearizeAtHover(params);
  std::vector<std::string> row_names(names.begin(), names.begin() + kMechStateSize);
  if (thesis_coordinates) {
    lin = ToSumDifferenceCoordinates(lin);
    row_names = {"x", "z", "phi", "b_s", "b_d", "x_dot", "z_dot", "phi_dot", "b_s_dot", "b_d_dot"};
  }
  PrintMatrix("Linearized A = d x_dot / d x at hover (rows: derivative of; columns in the same order)", lin.a,
              row_names);
  PrintMatrix("Linearized B = d x_dot / d [f1, f2]", lin.b, row_names);

  std::printf("\nArm modes at hover\n");
  for (const Mode& mode : OscillatoryModes(LinearizeAtHover(params).a))
    std::printf("  %8.3f Hz   damping ratio %.4f\n", mode.frequency_hz, mode.damping_ratio);

  const AugMatrix aug = AugmentWithForces(LinearizeAtHover(params));
  std::printf("\nObservability of the augmented system (12 states: x, z, phi, b1, b2, rates, f1, f2; thesis ch. 4)\n");
  std::printf("Balanced, time-scaled staircase test; sigma = singular values of the scaled observability matrix;\n");
  std::printf("PBH = smallest singular value of [A - lambda I; C] over the eigenvalues (0 means a hidden mode).\n\n");
  std::printf("| measured | rank | unobservable states | sigma max | sigma min | min PBH margin |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (size_t i = 0; i < measure_sets.size(); ++i) {
    const SubspaceReport r = AnalyzeObservability(aug, selections[i], names);
    std::printf("| %s | %d / %d | %s | %.3g | %.3g | %.3g |\n", measure_sets[i].c_str(), r.rank, r.state_size,
                Join(r.hidden_states).c_str(), r.singular_values.maxCoeff(), r.singular_values.minCoeff(),
                r.pbh_margins.minCoeff());
  }

  PrintParameterObservability(params);

  const SubspaceReport ctrb = AnalyzeControllability(LinearizeAtHover(params).a, LinearizeAtHover(params).b, row_names);
  std::printf(
      "\nControllability from [f1, f2] (10 mechanical states, thesis ch. 6): rank %d / %d; "
      "uncontrollable: %s; sigma min %.3g, min PBH margin %.3g\n",
      ctrb.rank, ctrb.state_size, Join(ctrb.hidden_states).c_str(), ctrb.singular_values.minCoeff(),
      ctrb.pbh_margins.minCoeff());
  return 0;
}

int Run(int argc, char** argv) {
  CLI::App app{
      "Model analysis of the birotor: equilibrium, linearization, modes, observability, controllability; with "
      "--vehicle, of any vehicle description"};
  app.option_defaults()->always_capture_default();
  std::string params_file = FindConfigFile("reference_vehicle.yaml");
  std::vector<std::string> measure_sets;
  bool thesis_coordinates = false;
  auto* params_option = app.add_option(
      "--params", params_file,
      "Parameter file with a complete vehicle: section; default: the " + ConfigSearchText("reference_vehicle.yaml"));
  auto* measure_option =
      app.add_option("--measure", measure_sets,
                     "Measured states, comma separated (repeatable), from: x,z,phi,b1,b2,x_dot,z_dot,phi_dot,"
                     "b1_dot,b2_dot,f1,f2. Default: the thesis's sets b1,b2 | x,z | all ten mechanical states");
  auto* thesis_flag =
      app.add_flag("--thesis-coordinates", thesis_coordinates, "Print A and B in b_s = b1 + b2, b_d = b1 - b2");
  std::string vehicle_file;
  std::vector<int> without_gauge;
  auto* vehicle_option =
      app.add_option("--vehicle", vehicle_file,
                     "Vehicle description file (N arms or the birotor form, docs/vehicle-description.md, e.g. "
                     "config/vehicles/trirotor.yaml): print its N-arm analysis (hover, arm modes, controllability, "
                     "force observability with and without IMU; docs/multi-arm-model.md) instead of the birotor "
                     "analysis of --params");
  app.add_option("--without-gauge", without_gauge,
                 "With --vehicle: analyse the vehicle with arm I's gauge removed (1-based, as in the file's arms: "
                 "list; repeatable or comma separated)")
      ->delimiter(',')
      ->needs(vehicle_option);
  vehicle_option->excludes(params_option)->excludes(measure_option)->excludes(thesis_flag);
  app.set_version_flag("--version", std::string("birotor-analyze ") + BIROTOR_VERSION);
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  if (!vehicle_file.empty()) return RunVehicleAnalysis(vehicle_file, without_gauge);

  return RunBirotorAnalysis(params_file, measure_sets, thesis_coordinates);
}

}  // namespace
}  // namespace birotor

int main(int argc, char** argv) { return birotor::Run(argc, argv); }
