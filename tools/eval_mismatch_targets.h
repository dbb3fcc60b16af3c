// birotor-eval --mismatch-targets: issue 36's flights (evaluation/mismatch_cases.h)
// on seeds 1..N with the estimator files as given, scored against the
// targets (evaluation/mismatch_targets.h); a measurement, not a gate.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "estimator/estimator_config.h"
#include "simulator/scenario.h"

namespace birotor {

// Loads a scenario by name with overrides; false with *error.
using ScenarioLoader = std::function<bool(const std::string& name, const std::vector<std::string>& overrides,
                                          Scenario* scenario, std::string* error)>;

struct MismatchTargetsRunOptions {
  int seeds = 5;                       // seeds 1..seeds of every case
  std::vector<std::string> overrides;  // --set, applied after each case's own (before the seed)
  std::string markdown_out;            // also written here (temporary file renamed), "" for none
};

// Prints the two tables (mismatched vehicles from 5 s, matching vehicles
// from 1 s); 0 unless a scenario cannot be loaded or the file written.
int RunMismatchTargets(const MismatchTargetsRunOptions& options, const EstimatorConfig& config,
                       const ScenarioLoader& load);

}  // namespace birotor
