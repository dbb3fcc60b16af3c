// birotor-identify --learned for a vehicle with N arms: the state file's r into every tip_mass_kg.
#include "tools/identify_learned_multi_arm.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "model/vehicle_description_checksum.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

// The description --update-params holds (from the text read once), and
// --vehicle's, which must be the same. Returns the refusal, "" on success.
std::string ReadDescription(const MultiArmLearnedRequest& request, const ParameterFileUpdate& update,
                            VehicleDescription* description) {
  try {
    *description = ParseVehicleDescription(update.text, request.update_params);
    if (request.vehicle.empty()) return "";
    const VehicleDescription flown = LoadVehicleDescription(request.vehicle);
    if (DescriptionChecksum(flown) != DescriptionChecksum(*description)) {
      const std::string difference = FirstDifference(*description, flown);
      return "--update-params " + request.update_params + " does not hold the description of --vehicle " +
             request.vehicle + " (" + (difference.empty() ? "checksum" : difference) +
             "): give the description the estimator flew, or a copy of it; nothing written";
    }
  } catch (const ParamError& e) {
    return e.what();
  }
  return "";
}

// text with every arm's tip_mass_kg set to deployed's, in the file's form
// (N-arm: the `arms:` list; birotor form: its one tip_mass_kg, the arms
// being scaled alike). Returns the error, "" on success.
std::string UpdatedText(const MultiArmLearnedRequest& request, const ParameterFileUpdate& update,
                        const VehicleDescription& deployed, const std::string& stamp, std::string* updated) {
  std::string error;
  if (IsArmsForm(update.text)) {
    std::vector<double> masses_kg;
    for (int i = 0; i < deployed.arm_count; ++i) masses_kg.push_back(deployed.arms[static_cast<size_t>(i)].tip_mass_kg);
    if (!UpdateDescriptionArmValues(update.text, "tip_mass_kg", masses_kg, stamp, updated, &error)) {
      return "--update-params " + request.update_params + ": " + error + "; file left unchanged";
    }
    return "";
  }
  try {
    if (!UpdateVehicleSection(update.text, BirotorModelOf(deployed), stamp, updated, &error)) {
      return "--update-params " + request.update_params + ": " + error + "; file left unchanged";
    }
  } catch (const std::invalid_argument& e) {
    return "--update-params " + request.update_params + ": " + e.what() + "; file left unchanged";
  }
  return "";
}

// The updated text must load (plausibility included) as the deployed
// description: each tip mass to the digits written, every other field
// unchanged. *written: what the file now describes. Returns the error.
std::string ReadBack(const MultiArmLearnedRequest& request, const std::string& updated,
                     const VehicleDescription& deployed, VehicleDescription* written) {
  try {
    *written = ParseVehicleDescription(updated, request.update_params);
  } catch (const ParamError& e) {
    return std::string(e.what()) + "; file left unchanged";
  }
  VehicleDescription expected = deployed;
  for (int i = 0; i < deployed.arm_count; ++i) {
    const size_t k = static_cast<size_t>(i);
    const double want_kg = deployed.arms[k].tip_mass_kg, got_kg = written->arms[k].tip_mass_kg;
    if (std::abs(got_kg - want_kg) <= 1e-9 * want_kg) expected.arms[k].tip_mass_kg = got_kg;  // 10 digits written
  }
  const std::string difference = FirstDifference(*written, expected);
  if (!difference.empty()) {
    return "--update-params " + request.update_params +
           ": the updated text does not read back as the deployed values (" + difference + "); file left unchanged";
  }
  return "";
}

// What the state file holds that is not deployed, and why (one info line).
void LogNotDeployed(const MultiArmGaugeState& state) {
  std::string offsets;
  for (int i = 0; i < state.arm_count; ++i) {
    const size_t k = static_cast<size_t>(i);
    offsets += fmt::format("{}{:.3e} +- {:.2e}", i > 0 ? ", " : "", state.offset_rad[k], state.offset_std_rad[k]);
  }
  spdlog::info(
      "not deployed: gauge offsets {} rad (a power-up value that drifts between flights; the estimator's offset "
      "states measure it at rest at each start, as the birotor's tare does, and the birotor does not deploy its "
      "offsets either)",
      offsets);
}

}  // namespace

std::string DeployLearnedMultiArm(const MultiArmLearnedRequest& request, const ParameterFileUpdate& update) {
  const LearnedSourceOptions& source = request.source;
  std::string error;
  VehicleDescription description;
  if (!(error = ReadDescription(request, update, &description)).empty()) return error;
  MultiArmGaugeState state;
  if (!(error = ReadTrustedVehicleState(source, description, &state)).empty()) return error;
  if (!state.has_tip_mass) {
    return source.learned +
           ": holds no learned tip mass (the estimator learns it with model_consistency arm_mode_learn_tip_mass "
           "on; its gauge offsets are not deployed): " +
           request.update_params + " not updated";
  }
  VehicleDescription deployed = description;
  std::vector<LearnedChange> changes;
  if (!ApplyLearnedTipMassRatio(state.tip_mass_ratio, state.tip_mass_ratio_std, request.deploy, source.learned,
                                request.update_params, &deployed, &changes, &error)) {
    return error;
  }
  const std::string stamp = request.stamp_time + " by birotor-identify from what the estimator learned (" +
                            std::filesystem::path(source.learned).filename().string() +
                            "): " + LearnedChangesText(changes);
  std::string updated;
  VehicleDescription written;
  if (!(error = UpdatedText(request, update, deployed, stamp, &updated)).empty() ||
      !(error = ReadBack(request, updated, deployed, &written)).empty()) {
    return error;
  }
  if (!CommitParameterFileUpdate(update, updated, &error)) return "--update-params: " + error;
  spdlog::info("learned: tip_mass_ratio {:.6g} +- {:.3g} (every arm's m_p,i): {}", state.tip_mass_ratio,
               state.tip_mass_ratio_std, LearnedChangesText(changes));
  LogNotDeployed(state);
  spdlog::info("updated the vehicle section of {} in place (previous file: {})", update.target, update.backup);
  spdlog::info(
      "description checksum {} -> {}: the estimator now refuses {} as another description's (one warning at its "
      "start) and flies the updated tip masses, learning afresh from them",
      DescriptionChecksum(description), DescriptionChecksum(written), source.learned);
  return "";
}

}  // namespace birotor
