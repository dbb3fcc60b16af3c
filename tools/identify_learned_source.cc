// birotor-identify --learned: a state file under the site key, a log re-run.
#include "tools/identify_learned_source.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>
#include <string>

#include "nodes/gauge_state_file.h"
#include "nodes/learned_values_file.h"
#include "nodes/recorded_tip_mass.h"
#include "nodes/vehicle_state_file.h"
#include "params/estimator_config_yaml.h"
#include "program/config_files.h"
#include "replay/learned_rerun.h"
#include "security/message_authenticator.h"
#include "security/site_key.h"
#include "transport/channels.h"

namespace birotor {
namespace {

// The site key of --site-key; "" on success, else the refusal of the state file.
std::string LoadSiteKey(const LearnedSourceOptions& options, SiteKey* key) {
  std::string error;
  if (!SiteKey::Load(options.site_key_file, key, &error)) {
    return "--learned: gauge state file " + options.learned + " is not authenticated (" + error +
           "): not deployed, nothing written";
  }
  return "";
}

// The state file's strain scales, its mac verified under the site key (the
// estimator's check, services/birotor_estimator_main.cc).
std::string FromStateFile(const LearnedSourceOptions& options, const std::string& vehicle_checksum,
                          LearnedVehicleValues* learned) {
  SiteKey key(SiteKey::Bytes{});
  std::string error = LoadSiteKey(options, &key);
  if (!error.empty()) return error;
  const MessageAuthenticator authenticator(key);
  if (!ReadLearnedState(options.learned, vehicle_checksum, authenticator, learned, &error)) {
    return "--learned " + error + ": not deployed, nothing written";
  }
  return "";
}

// The estimator file of the re-run, with the vehicle the values are deployed into.
std::string RerunConfig(const LearnedSourceOptions& options, const BirotorParams& vehicle, EstimatorConfig* config) {
  const std::string file =
      options.estimator_config.empty() ? FindConfigFile("estimator.yaml") : options.estimator_config;
  try {
    *config = LoadEstimatorConfig(file);
  } catch (const std::exception& e) {
    return std::string("--estimator-config: ") + e.what();
  }
  config->vehicle = BirotorDescription(vehicle);
  spdlog::info("re-running {} over the inputs of {} (estimator file {})", config->method, options.learned, file);
  return "";
}

// The log's newest learned tip mass (ESTIMATOR_LEARNED_N) in *recorded,
// false when it has none; a refusal (another vehicle, out of range) in *refusal.
bool ReadCheckedTipMass(const LearnedSourceOptions& options, const BirotorParams& vehicle,
                        const std::string& update_params, RecordedTipMass* recorded, std::string* refusal) {
  std::string error;
  const std::string channel = MakeChannelNames(options.prefix).estimator_learned_n;
  if (!ReadRecordedTipMass(options.learned, channel, recorded, &error)) {
    spdlog::info("{}; the tip mass, if learned, is the re-run's", error);
    return false;
  }
  *refusal = RecordedTipMassRefusal(options.learned, *recorded, BirotorDescription(vehicle), update_params);
  return true;
}

// The recorded tip mass in place of the re-run's where the log's own inputs
// support it: the re-run learned it, the recorded value lies within
// kRecordedTipMassSigmas of the re-run's sigma of it, and claims no more
// than the re-run's sigma. It is what the estimator flew, and after a
// resume from the state file it holds earlier flights' readings too; a
// forged message can move the deployed m_p by no more than the inputs'
// own uncertainty. Else the re-run's, with a warning naming the key.
constexpr double kRecordedTipMassSigmas = 3.0;

void UseRecordedTipMass(const std::string& log, const RecordedTipMass& recorded, LearnedVehicleValues* learned) {
  const std::string said = fmt::format("{}: tip_mass_kg: the log's ESTIMATOR_LEARNED_N says {:.6g} +- {:.3g} kg", log,
                                       recorded.tip_mass_kg, recorded.tip_mass_std_kg);
  if (!learned->has_tip_mass) {
    spdlog::warn(
        "{}, but the re-run of its inputs did not learn it (--estimator-config: the flight's file, "
        "arm_mode_learn_tip_mass on): the recorded value was not used",
        said);
    return;
  }
  const double sigmas = std::abs(recorded.tip_mass_kg - learned->tip_mass_kg) / learned->tip_mass_std_kg;
  if (!(sigmas <= kRecordedTipMassSigmas) || !(recorded.tip_mass_std_kg <= learned->tip_mass_std_kg)) {
    spdlog::warn(
        "{}, its inputs re-run give {:.6g} +- {:.3g} kg ({:.1f} of the re-run's sigmas apart, at most {:g} "
        "with no wider sigma): the recorded value was not used",
        said, learned->tip_mass_kg, learned->tip_mass_std_kg, sigmas, kRecordedTipMassSigmas);
    return;
  }
  spdlog::info("{} (source {}), deployed: the re-run of its inputs gives {:.6g} +- {:.3g} kg", said, recorded.source,
               learned->tip_mass_kg, learned->tip_mass_std_kg);
  learned->tip_mass_kg = recorded.tip_mass_kg;
  learned->tip_mass_std_kg = recorded.tip_mass_std_kg;
}

// What the log's inputs support, compared with its recorded status.
std::string FromLog(const LearnedSourceOptions& options, const BirotorParams& vehicle, const std::string& update_params,
                    LearnedVehicleValues* learned) {
  const std::string vehicle_checksum = VehicleChecksum(vehicle);
  LearnedVehicleValues recorded;
  std::string recorded_checksum, error;
  const bool has_recorded =
      ReadRecordedLearnedValues(options.learned, options.prefix, &recorded, &recorded_checksum, &error);
  if (!has_recorded) spdlog::info("{}; nothing recorded to compare with the re-run", error);
  if (has_recorded && recorded_checksum != vehicle_checksum) {
    // Guards against deploying one flight twice (the file changed since).
    return "--learned " + options.learned + ": its newest ESTIMATOR_STATUS with a learned value was flown with " +
           "another vehicle or parameter file (vehicle checksum '" + recorded_checksum + "', " + update_params +
           " now " + vehicle_checksum + "): not deployed, nothing written";
  }
  RecordedTipMass recorded_tip_mass;
  std::string refusal;
  const bool has_tip_mass = ReadCheckedTipMass(options, vehicle, update_params, &recorded_tip_mass, &refusal);
  if (!refusal.empty()) return refusal;
  EstimatorConfig config;
  if (!(error = RerunConfig(options, vehicle, &config)).empty()) return error;
  LearnedRerun rerun;
  if (!RelearnFromLog(options.learned, config, options.prefix, options.min_usable_fraction, &rerun, &error)) {
    return "--learned " + error + ": nothing written";
  }
  if (!rerun.damage.empty()) spdlog::warn("{}", rerun.damage);
  const ReplayStats& stats = rerun.stats;
  spdlog::info("re-run: {} input packets, {} FORCE estimates over {:.1f} s of the log", stats.input_packets,
               stats.forces, static_cast<double>(stats.last_utime - stats.first_utime) * 1e-6);
  for (const LearnedDisagreement& d : CompareLearnedValues(recorded, rerun.learned)) {
    spdlog::warn("{}: {}", options.learned, DisagreementText(d));
  }
  *learned = rerun.learned;
  if (has_tip_mass) UseRecordedTipMass(options.learned, recorded_tip_mass, learned);
  return "";
}

}  // namespace

std::string ReadTrustedLearnedValues(const LearnedSourceOptions& options, const BirotorParams& vehicle,
                                     const std::string& update_params, LearnedVehicleValues* learned) {
  if (IsLcmLog(options.learned)) return FromLog(options, vehicle, update_params, learned);
  return FromStateFile(options, VehicleChecksum(vehicle), learned);
}

std::string ReadTrustedVehicleState(const LearnedSourceOptions& options, const VehicleDescription& vehicle,
                                    MultiArmGaugeState* state) {
  if (IsLcmLog(options.learned)) {
    return "--learned " + options.learned +
           ": a flight log; for a vehicle with N arms only its gauge state file is deployed (the estimator's "
           "tare.state_file): nothing written";
  }
  SiteKey key(SiteKey::Bytes{});
  std::string error = LoadSiteKey(options, &key);
  if (!error.empty()) return error;
  // The offsets are not deployed (the offset states measure them at rest at
  // each start, as the birotor's tare): no bound on them here.
  const double any_offset = std::numeric_limits<double>::infinity();
  if (!ReadVehicleGaugeState(options.learned, VehicleStateChecksum(vehicle), vehicle.arm_count, any_offset,
                             MessageAuthenticator(key), state, &error)) {
    return "--learned " + error + ": not deployed, nothing written";
  }
  return "";
}

}  // namespace birotor
