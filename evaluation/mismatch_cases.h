// The flights of issue 36 ("The estimator learns the vehicle it flies"):
// vehicles that differ from the estimator's parameter file, each a shipped
// scenario plus scenario overrides (the syntax of --set), flown with the
// shipped estimator files unchanged; and the matching-vehicle flights a
// later change is compared against. birotor-eval --mismatch-targets flies
// them (docs/mismatch.md, "Issue 36: the measurement").
#pragma once

#include <string>
#include <vector>

namespace birotor {

struct MismatchCase {
  std::string name;                    // table label
  std::string scenario;                // scenarios/<scenario>.yaml
  std::vector<std::string> overrides;  // section.key=value, applied in order (the seed after them)
};

// Issue 36's list, in its order (docs/mismatch.md lists the values).
const std::vector<MismatchCase>& VehicleMismatchCases();

// The shipped scenarios with the vehicle their file describes: hover,
// gentle, aggressive, thrust_loss.
const std::vector<MismatchCase>& MatchingVehicleCases();

// "Every vehicle parameter different by 5-30 % at once": the fixed set of
// overrides (factors on config/reference_vehicle.yaml in the comment of
// mismatch_cases.cc).
std::vector<std::string> EveryParameterDifferentOverrides();

}  // namespace birotor
