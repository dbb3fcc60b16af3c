// Building ESTIMATOR_LEARNED_N (lcmtypes/estimator_learned_n_t.lcm), the
// per-arm companion of ESTIMATOR_STATUS: the strain scales, tip masses and
// gauge noise the estimator flies and the body mass, each with its sigma and
// where it comes from, for the birotor's pipeline and for the N-arm one.
#pragma once

#include <string>

#include "birotor/estimator_learned_n_t.hpp"
#include "birotor/estimator_status_t.hpp"
#include "estimator/estimator_config.h"
#include "estimator/estimator_pipeline.h"
#include "estimator/multi_arm_pipeline.h"
#include "model/vehicle_description.h"

namespace birotor {

// Sizes message's arrays to vehicle.arm_count and sets the checksum
// (DescriptionChecksum of vehicle): once, at start, so that filling it
// allocates nothing.
void PrepareEstimatorLearned(const VehicleDescription& vehicle, estimator_learned_n_t* message);

// The birotor's pipeline: the strain scales and body mass as ESTIMATOR_STATUS
// has them, the tip mass it flies (learned by the arm-mode test, one m_p for
// both arms, or the file's), and each gauge's noise sqrt(scale_i)
// strain_noise_rad. utime and seq are status's, the ESTIMATOR_STATUS it goes
// out with. config: the pipeline's (its file values).
void FillEstimatorLearned(const PipelineHealth& health, const EstimatorConfig& config, const estimator_status_t& status,
                          estimator_learned_n_t* message);

// The N-arm pipeline: it learns each gauge's noise only; the strain scales
// (1), the tip masses and the body mass are the description's, source
// "params", sigma NaN.
void FillEstimatorLearned(const MultiArmPipelineHealth& health, const EstimatorConfig& config,
                          const estimator_status_t& status, estimator_learned_n_t* message);

}  // namespace birotor
