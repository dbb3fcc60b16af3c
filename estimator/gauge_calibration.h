// Strain-gauge calibration (shared/spec/gauges.md): a gauge reads
// b_meas_i = s_i b_i + o_i, so the deflection the models use is
// b_i = (b_meas_i - o_i) / s_i. The scale comes from the vehicle parameter
// file; the offset from the file, a tare on the ground or the persisted state.
#pragma once

#include "model/birotor_dynamics.h"
#include "model/birotor_params.h"
#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

// Where the offset in use comes from (ESTIMATOR_STATUS gauge_offset_source).
enum class GaugeOffsetSource : int { kParameters = 0, kTare = 1, kStateFile = 2 };
const char* GaugeOffsetSourceName(GaugeOffsetSource source);  // "params", "tare", "state_file"

struct GaugeCalibration {
  double scale[kBirotorRotors] = {1.0, 1.0};       // s_i [1]
  double offset_rad[kBirotorRotors] = {0.0, 0.0};  // o_i [rad]
  double offset_std_rad[kBirotorRotors] = {0, 0};  // one sigma of o_i [rad]
  GaugeOffsetSource source = GaugeOffsetSource::kParameters;
  // The strain scale g_i learned in flight (EkfOptions::learn_strain_scale,
  // docs/mismatch.md): the calibrated gauge reads g_i b_i + e_i, g_i = true
  // gauge scale over s_i times the file's stiffness over the true one.
  // Persisted with the offsets; not applied by Apply (the filter holds it).
  bool has_strain_scale = false;
  double strain_scale[kBirotorRotors] = {1.0, 1.0};      // g_i [1]
  double strain_scale_std[kBirotorRotors] = {0.0, 0.0};  // [1]
  // The tip mass m_p learned from the arm mode (model_consistency
  // arm_mode_learn_tip_mass, docs/mismatch.md): persisted with the offsets
  // for `birotor-identify --update-params FILE --learned STATE`, and where
  // the next start's learning starts (EstimatorPipeline::SetGaugeOffsets:
  // flown from the first sample with its sigma while learning is on; the
  // file's m_p with it off). Not applied by Apply.
  bool has_tip_mass = false;
  double tip_mass_kg = 0.0;      // [kg]
  double tip_mass_std_kg = 0.0;  // [kg]

  // gauge_scale, gauge_offset_rad and gauge_offset_std_rad of the vehicle.
  static GaugeCalibration FromVehicle(const BirotorParams& params) {
    GaugeCalibration c;
    for (int i = 0; i < kBirotorRotors; ++i) {
      c.scale[i] = params.gauge_scale[i];
      c.offset_rad[i] = params.gauge_offset_rad[i];
      c.offset_std_rad[i] = params.gauge_offset_std_rad;
    }
    return c;
  }
  // b_i = (b_meas_i - o_i) / s_i for both arms; utime and seq are kept.
  StrainSample Apply(const StrainSample& reading) const {
    StrainSample out = reading;
    for (int i = 0; i < kBirotorRotors; ++i)
      out.deflection_rad[i] = (reading.deflection_rad[i] - offset_rad[i]) / scale[i];
    return out;
  }
};

// What gauge i reads at rest on the ground with the motors stopped, before
// its offset: s_i b_rest_i with b_rest_i = StaticDeflectionRad(f = 0) [rad].
inline double RestReadingRad(const BirotorParams& params, int arm) {
  return params.gauge_scale[arm] * StaticDeflectionRad(params, arm, 0.0);
}

}  // namespace birotor
