// birotor-eval --vehicle FILE: the N-arm methods' accuracy table
// (evaluation/multi_arm_accuracy.h) on the named scenarios, flown by the
// N-arm simulator in-process and lock-step; with --log LOG, of the FORCE_N
// in a log against its TRUTH_N (a live run recorded by lcm-logger).
#pragma once

#include <string>
#include <vector>

#include "estimator/estimator_config.h"
#include "evaluation/eval_metrics.h"

namespace birotor {

// Loads the description (refusing one that cannot fly) and each scenario
// for its arm count with the overrides (--set), runs each method on each,
// prints the table (methods empty: estimator.method); returns the exit status (kExitFailure on a bad file or
// scenario, or a method without an N-arm version). scenarios_named: the user
// named them (--scenarios); else a default scenario whose per-arm lists do
// not fit the vehicle (the birotor's two gauge offsets for three arms) is
// skipped with its one-line reason under the table, not an error.
int RunMultiArmAccuracyMode(const std::string& vehicle_file, const std::vector<std::string>& scenarios,
                            bool scenarios_named, const std::vector<std::string>& methods,
                            const std::vector<std::string>& overrides, const EstimatorConfig& estimator,
                            const EvalOptions& options);
// The row of the log (prefix: its channel prefix); the exit status.
int RunMultiArmLogAccuracy(const std::string& vehicle_file, const std::string& log_path, const std::string& prefix,
                           const EvalOptions& options);

}  // namespace birotor
