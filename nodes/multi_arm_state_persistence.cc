#include "nodes/multi_arm_state_persistence.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include "nodes/vehicle_state_file.h"

namespace birotor {
namespace {

// Whether the persisted tip mass is flown (learning on: it resumes from it)
// or not (the description's m_p,i).
void LogResumedTipMass(const MultiArmGaugeState& persisted, const MultiArmPipelineHealth& health,
                       const std::string& path) {
  if (health.tip_mass_from_state_file) {
    spdlog::info(
        "tip masses {:.6g} +- {:.3g} times the description's from the state file {}: flown, learning "
        "resumes from them",
        persisted.tip_mass_ratio, persisted.tip_mass_ratio_std, path);
  } else {
    spdlog::info(
        "tip masses {:.6g} +- {:.3g} times the description's in the state file {} not flown "
        "(model_consistency arm_mode_learn_tip_mass off, or no arm mode to learn from): the description's",
        persisted.tip_mass_ratio, persisted.tip_mass_ratio_std, path);
  }
}

}  // namespace

bool RestoreVehicleGaugeState(const std::string& path, const EstimatorConfig& config,
                              const MessageAuthenticator& authenticator, MultiArmEstimatorService* service) {
  if (access(path.c_str(), F_OK) != 0) {
    spdlog::info("gauge state file {} absent: gauge offsets from the vehicle description", path);
    return false;
  }
  MultiArmGaugeState persisted;
  std::string error;
  if (!ReadVehicleGaugeState(path, VehicleStateChecksum(config.vehicle), config.vehicle.arm_count,
                             config.tare.max_offset_rad, authenticator, &persisted, &error)) {
    spdlog::warn("gauge state file refused: {}; gauge offsets from the vehicle description", error);
    return false;
  }
  service->ResumeGaugeState(persisted);
  std::string offsets;
  for (int i = 0; i < persisted.arm_count; ++i) {
    offsets += fmt::format("{}{:.3e}", i > 0 ? " " : "", persisted.offset_rad[static_cast<size_t>(i)]);
  }
  spdlog::info("gauge offsets {} rad from the state file {}", offsets, path);
  if (persisted.has_tip_mass) LogResumedTipMass(persisted, service->health(), path);
  return true;
}

bool PersistVehicleGaugeState(const std::string& path, const MultiArmEstimatorService& service,
                              const MessageAuthenticator& authenticator, std::string* error) {
  const MultiArmGaugeState state = service.GaugeState();
  if (!WriteVehicleGaugeState(path, state, VehicleStateChecksum(service.vehicle()), authenticator, error)) {
    return false;
  }
  spdlog::info("gauge offsets ({}){} written to {}", GaugeOffsetSourceName(state.source),
               state.has_tip_mass ? ", learned tip masses" : "", path);
  return true;
}

}  // namespace birotor
