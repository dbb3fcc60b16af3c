// Learned strain scales, body mass and tip mass into the vehicle parameters (docs/identification.md).
#include "params/learned_parameter_update.h"

#include <cmath>
#include <cstdio>

#include "params/birotor_params_yaml.h"
#include "params/yaml_reader.h"

namespace birotor {
namespace {

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

// The range of a key (body_mass_kg, tip_mass_kg) in the vehicle key table (one table).
void KeyRange(const char* name, double* min, double* max) {
  for (const VehicleKey& key : VehicleKeys()) {
    if (std::string(key.name) == name) {
      *min = key.min;
      *max = key.max;
    }
  }
}

// "not finite" / "not learned" check of one value; empty when it may be deployed.
std::string CheckLearned(const std::string& learned_file, const std::string& name, double value, double sigma,
                         double prior_sigma, const LearnedDeployOptions& options, const std::string& key,
                         const std::string& file) {
  if (!std::isfinite(value) || !std::isfinite(sigma) || sigma < 0) {
    return learned_file + ": " + name + " " + Number(value) + " +- " + Number(sigma) +
           (sigma < 0 ? " has a negative sigma: " : " is not finite: ") + file + " " + key + " not updated";
  }
  const double limit = options.max_std_fraction * prior_sigma;
  if (!(sigma < limit)) {
    return learned_file + ": " + name + " " + Number(value) + " +- " + Number(sigma) +
           " was not learned (sigma not below " + Number(options.max_std_fraction) + " x the prior sigma " +
           Number(prior_sigma) + " = " + Number(limit) +
           ", --learned-max-std-fraction; fly longer in free flight): " + file + " " + key + " not updated";
  }
  return "";
}

std::string OutOfRange(const std::string& file, const std::string& key, double value, double min, double max,
                       const std::string& why) {
  return file + ": " + key + " would become " + Number(value) + " (" + why + "), outside " + RangeText(min, max) +
         ": refused, file not updated";
}

// One learned mass (name: body_mass_kg or tip_mass_kg) into *in_file [kg]:
// checked against its prior (prior_fraction x the file's value) and the key's
// range; false with *error naming the file and the key.
bool DeployLearnedMass(const std::string& learned_file, const std::string& file, const LearnedDeployOptions& options,
                       const char* name, const char* what, double mass_kg, double sigma_kg, double prior_fraction,
                       double* in_file, std::vector<LearnedChange>* made, std::string* error) {
  const std::string key = std::string("vehicle.") + name;
  *error = CheckLearned(learned_file, name, mass_kg, sigma_kg, prior_fraction * *in_file, options, key, file);
  if (!error->empty()) return false;
  double min = 0, max = 0;
  KeyRange(name, &min, &max);
  if (!(mass_kg >= min && mass_kg <= max)) {
    *error = OutOfRange(file, key, mass_kg, min, max, what);
    return false;
  }
  made->push_back({name, *in_file, mass_kg, mass_kg, sigma_kg});
  *in_file = mass_kg;
  return true;
}

}  // namespace

bool ApplyLearnedValues(const LearnedVehicleValues& learned, const LearnedDeployOptions& options,
                        const std::string& learned_file, const std::string& file, BirotorParams* vehicle,
                        std::vector<LearnedChange>* changes, std::string* error) {
  if (!learned.has_strain_scale && !learned.has_body_mass && !learned.has_tip_mass) {
    *error = learned_file +
             ": holds no learned strain scale, body mass or tip mass (the estimator learns them with "
             "estimator.ekf learn_strain_scale / learn_body_mass, model_consistency arm_mode_learn_tip_mass on): " +
             file + " not updated";
    return false;
  }
  BirotorParams updated = *vehicle;
  std::vector<LearnedChange> made;
  for (int arm = 0; learned.has_strain_scale && arm < 2; ++arm) {
    const std::string key = "vehicle.gauge_scale[" + std::to_string(arm) + "]";
    const double g = learned.strain_scale[arm], sigma = learned.strain_scale_std[arm];
    *error = CheckLearned(learned_file, "strain_scale of arm " + std::to_string(arm + 1), g, sigma,
                          options.strain_scale_prior_std, options, key, file);
    if (!error->empty()) return false;
    // z = g_i b + e_i in the calibrated deflection: a gauge scale of g_i s_i
    // gives the deflection the file's stiffness predicts.
    const double scale = vehicle->gauge_scale[arm] * g;
    if (!(scale >= kGaugeScaleMin && scale <= kGaugeScaleMax)) {
      *error = OutOfRange(file, key, scale, kGaugeScaleMin, kGaugeScaleMax,
                          Number(vehicle->gauge_scale[arm]) + " x learned strain scale " + Number(g));
      return false;
    }
    updated.gauge_scale[arm] = scale;
    made.push_back({key.substr(8), vehicle->gauge_scale[arm], scale, g, sigma});
  }
  if (learned.has_body_mass &&
      !DeployLearnedMass(learned_file, file, options, "body_mass_kg", "the learned body mass", learned.body_mass_kg,
                         learned.body_mass_std_kg, options.body_mass_scale_prior_std, &updated.body_mass_kg, &made,
                         error))
    return false;
  // The tip mass's prior is relative to the file's, as the arm-mode test's.
  if (learned.has_tip_mass &&
      !DeployLearnedMass(learned_file, file, options, "tip_mass_kg", "the learned tip mass", learned.tip_mass_kg,
                         learned.tip_mass_std_kg, options.tip_mass_prior_std, &updated.tip_mass_kg, &made, error))
    return false;
  error->clear();
  *vehicle = updated;
  *changes = made;
  return true;
}

bool ApplyLearnedTipMassRatio(double ratio, double ratio_std, const LearnedDeployOptions& options,
                              const std::string& learned_file, const std::string& file, VehicleDescription* vehicle,
                              std::vector<LearnedChange>* changes, std::string* error) {
  // The prior of r is the tip mass's relative prior: r = 1 +- 0.15.
  *error = CheckLearned(learned_file, "tip_mass_ratio", ratio, ratio_std, options.tip_mass_prior_std, options,
                        "vehicle.arms[*].tip_mass_kg", file);
  if (!error->empty()) return false;
  double min = 0, max = 0;
  KeyRange("tip_mass_kg", &min, &max);  // the N-arm key's range is the birotor key's
  VehicleDescription updated = *vehicle;
  std::vector<LearnedChange> made;
  for (int arm = 0; arm < vehicle->arm_count; ++arm) {
    const std::string key = "arms[" + std::to_string(arm) + "].tip_mass_kg";
    double& mass_kg = updated.arms[static_cast<size_t>(arm)].tip_mass_kg;
    const double scaled_kg = ratio * mass_kg;
    if (!(scaled_kg >= min && scaled_kg <= max)) {
      *error = OutOfRange(file, "vehicle." + key, scaled_kg, min, max,
                          Number(mass_kg) + " x learned tip_mass_ratio " + Number(ratio));
      return false;
    }
    made.push_back({key, mass_kg, scaled_kg, ratio, ratio_std});
    mass_kg = scaled_kg;
  }
  error->clear();
  *vehicle = updated;
  *changes = made;
  return true;
}

std::string LearnedChangesText(const std::vector<LearnedChange>& changes) {
  std::string text;
  for (const LearnedChange& c : changes) {
    if (!text.empty()) text += "; ";
    text += c.key + " " + Number(c.old_value) + " -> " + Number(c.new_value) + " (learned " + Number(c.learned) +
            " +- " + Number(c.learned_std) + ")";
  }
  return text;
}

}  // namespace birotor
