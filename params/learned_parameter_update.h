// Deploying what the estimator learned in flight (issue 27 item 2) into a
// parameter file: `birotor-identify --update-params FILE --learned STATE`.
// The flight determines per arm the strain scale g_i = (true gauge scale /
// s_i) x (k_file / k_true) and the body mass, not gauge scale and stiffness
// apart; the file keeps an equivalent model by multiplying gauge_scale[i] by
// g_i (the calibrated deflection (z - o_i) / (g_i s_i) is then the one the
// file's stiffness predicts) and by writing the learned body mass into
// body_mass_kg. The tip mass learned from the arm mode (issue 36) is written
// into tip_mass_kg. The reference file carries no sigma key for any of them,
// so no sigma key is written: the sigma is in the log line and the stamp
// (docs/identification.md).
#pragma once

#include <string>
#include <vector>

#include "estimator/estimator_config.h"
#include "model/birotor_params.h"
#include "model/vehicle_description.h"
#include "samples/rotor_count.h"

namespace birotor {

// What the estimator learned, as read from a gauge state file or from the
// last ESTIMATOR_STATUS of a flight log.
struct LearnedVehicleValues {
  bool has_strain_scale = false;
  double strain_scale[kBirotorRotors] = {1, 1};      // g_i [1]
  double strain_scale_std[kBirotorRotors] = {0, 0};  // one sigma [1]
  bool has_body_mass = false;
  double body_mass_kg = 0;      // [kg]
  double body_mass_std_kg = 0;  // one sigma [kg]
  bool has_tip_mass = false;    // m_p of both arms, learned from the arm mode
  double tip_mass_kg = 0;       // [kg]
  double tip_mass_std_kg = 0;   // one sigma [kg]
};

// When a learned value counts as learned.
struct LearnedDeployOptions {
  // A value is deployed only when its sigma is below this fraction of its
  // prior sigma (--learned-max-std-fraction): the flight must have at least
  // halved the prior's uncertainty.
  double max_std_fraction = 0.5;
  // The prior sigmas the estimator starts from (estimator.yaml ekf:
  // strain_scale_prior_std, body_mass_scale_prior_std, relative): the
  // defaults of EkfOptions, 0.1 and 0.15.
  double strain_scale_prior_std = EkfOptions{}.strain_scale_prior_std;        // [1]
  double body_mass_scale_prior_std = EkfOptions{}.body_mass_scale_prior_std;  // relative to body_mass_kg [1]
  // The tip mass's prior (model_consistency: arm_mode_unconfirmed_tip_mass_std,
  // 0.15 of the file's tip_mass_kg).
  double tip_mass_prior_std = ModelConsistencyOptions{}.arm_mode_unconfirmed_tip_mass_std;  // relative [1]
};

// One key written, for the log and the stamp.
struct LearnedChange {
  std::string key;  // "gauge_scale[0]", "gauge_scale[1]", "body_mass_kg", "tip_mass_kg", "arms[0].tip_mass_kg"
  double old_value = 0;
  double new_value = 0;
  double learned = 0;      // g_i, the body or tip mass [kg], or the N-arm tip-mass ratio r
  double learned_std = 0;  // its one sigma
};

// Applies every learned value of `learned` (read from learned_file) to
// *vehicle (the vehicle `file` describes now): gauge_scale[i] *= g_i,
// body_mass_kg = the learned mass, tip_mass_kg = the learned m_p. All or
// nothing: false with a one-line *error naming the file, the key and the
// range, *vehicle unchanged, when nothing was learned, or a value is not
// finite, not learned (sigma not below max_std_fraction x its prior sigma),
// or would leave its key's range (gauge_scale [0.5, 2], body_mass_kg and
// tip_mass_kg the vehicle table's range).
bool ApplyLearnedValues(const LearnedVehicleValues& learned, const LearnedDeployOptions& options,
                        const std::string& learned_file, const std::string& file, BirotorParams* vehicle,
                        std::vector<LearnedChange>* changes, std::string* error);

// A vehicle with N arms (birotor-estimator --vehicle): its gauge state file
// (nodes/vehicle_state_file.h) holds the tip-mass ratio r the arm-mode test
// learned, one r by which every arm's m_p,i of the description is scaled.
// Sets every arm's tip_mass_kg of *vehicle (the description `file` holds
// now) to r x its own, one change per arm (learned: r and its sigma). All or
// nothing, as ApplyLearnedValues: false with a one-line *error naming the
// file and the key, *vehicle unchanged, when r is not finite, not learned
// (its sigma not below max_std_fraction x tip_mass_prior_std: r's prior is
// the tip mass's relative one), or an arm's mass would leave tip_mass_kg's
// range.
bool ApplyLearnedTipMassRatio(double ratio, double ratio_std, const LearnedDeployOptions& options,
                              const std::string& learned_file, const std::string& file, VehicleDescription* vehicle,
                              std::vector<LearnedChange>* changes, std::string* error);

// "gauge_scale[0] 1 -> 0.7032 (g 0.7032 +- 0.0041)", one per change, "; " between.
std::string LearnedChangesText(const std::vector<LearnedChange>& changes);

}  // namespace birotor
