#include "tools/eval_mismatch_targets.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>

#include "evaluation/eval_runner.h"
#include "evaluation/mismatch_cases.h"
#include "evaluation/mismatch_targets.h"
#include "program/program_options.h"
#include "transport/output_file.h"

namespace birotor {
namespace {

// One case on every seed: its figures, or false with *error.
bool FlyCase(const MismatchCase& c, const MismatchTargetsRunOptions& options, const EstimatorConfig& config,
             const MismatchTargets& targets, const ScenarioLoader& load, std::vector<MismatchTargetFigures>* figures,
             std::string* error) {
  for (int seed = 1; seed <= options.seeds; ++seed) {
    std::vector<std::string> overrides = c.overrides;
    overrides.insert(overrides.end(), options.overrides.begin(), options.overrides.end());
    overrides.push_back("scenario.seed=" + std::to_string(seed));
    Scenario scenario;
    if (!load(c.scenario, overrides, &scenario, error)) return false;
    const EvalRun run = RunSimulatedScenario(scenario, config);
    figures->push_back(EvaluateMismatchTargets(run.forces, run.truth, run.liftoff_utime, targets));
    const MismatchTargetFigures& f = figures->back();
    spdlog::info("{} seed {}: {:.1f} s flown in {:.2f} s; VALID {:.3f}, MAE {:.3f} N, 2-sigma {:.3f}, window {:.3f}",
                 c.name, seed, run.simulated_s, run.wall_s, f.valid_share, f.valid_mae_n, f.two_sigma_share,
                 f.worst_window_share);
  }
  return true;
}

// One table: the header for these targets and a row per case.
bool Table(const std::vector<MismatchCase>& cases, const MismatchTargets& targets,
           const MismatchTargetsRunOptions& options, const EstimatorConfig& config, const ScenarioLoader& load,
           std::string* table, std::string* error) {
  *table += MismatchTargetsTableHeader(targets);
  for (const MismatchCase& c : cases) {
    std::vector<MismatchTargetFigures> figures;
    if (!FlyCase(c, options, config, targets, load, &figures, error)) return false;
    *table += MismatchTargetsTableRow(c.name, figures, targets);
  }
  return true;
}

}  // namespace

int RunMismatchTargets(const MismatchTargetsRunOptions& options, const EstimatorConfig& config,
                       const ScenarioLoader& load) {
  OutputFile markdown;
  std::string error;
  if (!options.markdown_out.empty() && !markdown.Open(options.markdown_out, &error)) return ReportError(error);
  const auto start = std::chrono::steady_clock::now();
  // Matching vehicles: from 1 s on (the estimator's start-up), for a later change to compare with.
  MismatchTargets matching;
  matching.settle_s = 1.0;
  std::string table = "Vehicles that differ from the estimator's file (issue 36):\n\n";
  std::string matching_table = "\nThe vehicles the files describe:\n\n";
  if (!Table(VehicleMismatchCases(), MismatchTargets(), options, config, load, &table, &error) ||
      !Table(MatchingVehicleCases(), matching, options, config, load, &matching_table, &error)) {
    return ReportError(error);
  }
  table += matching_table;
  std::printf("%s", table.c_str());
  if (std::fflush(stdout) != 0) return ReportError("writing the table to standard output failed");
  spdlog::info("--mismatch-targets: {} flights in {:.0f} s",
               options.seeds * (VehicleMismatchCases().size() + MatchingVehicleCases().size()),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  if (markdown.is_open()) {
    markdown.Write(table);
    if (!markdown.Commit(&error)) return ReportError(error);
  }
  return 0;
}

}  // namespace birotor
