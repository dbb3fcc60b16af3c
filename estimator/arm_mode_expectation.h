// What the file lets an arm mode be: the mode the arm-mode test listens to
// (estimator/arm_mode_monitor.h) on the birotor and on any described
// vehicle, its frequency range, and what a tip-mass error puts into each
// force. Pure library, computed once at start-up.
#pragma once

#include "model/birotor_params.h"
#include "model/vehicle_description.h"
#include "samples/multi_arm_samples.h"
#include "samples/rotor_count.h"

namespace birotor {

// The symmetric arm mode (both arms flapping together, seen in b1 - b2) of
// the hover linearisation of params (model/linearization.h, the figure
// birotor-analyze prints): the lower of the two oscillatory modes [Hz].
double SymmetricArmModeHz(const BirotorParams& params);
// Arm mode `index` (by frequency, MultiArmModeShapes) of a described
// vehicle's hover linearisation [Hz]; 0 when it has none.
double ArmModeHz(const VehicleDescription& vehicle, int index);

// What the file lets the symmetric mode be [Hz]. A gauge scale s_i in the
// file is ambiguous for the arm's dynamics: a gauge that really reads s_i
// (the mode is the file's), or a stiffness k / s_i the static reading cannot
// tell from it (birotor-identify --learned writes a learned strain scale,
// which may be a stiffness, into gauge_scale; docs/mismatch.md). The mode
// may lie anywhere between; with the ideal gauge the range is the point.
struct ArmModeExpectation {
  double file_hz = 0;  // the file's, gauges as they are (0: no test)
  double low_hz = 0;   // lowest and highest the file allows
  double high_hz = 0;
  // d ln f / d ln k at the file: how the mode moves with the arm stiffness
  // (0.5 for a lone spring and mass; the body's coupling moves it) [1].
  double stiffness_exponent = 0.5;
  // m_p g of the file: what a tip-mass error of 100 % puts into each
  // strain-derived force at hover (docs/mismatch.md) [N].
  double tip_weight_n = 0;
  // The gauge readings that hold the mode: sum_i weights[i] b_i over the
  // first `arms` readings as the method gets them (the birotor's calibrated
  // b1 - b2; for N arms the raw readings, each weight over its gauge's
  // scale) [1/rad of reading].
  int arms = kBirotorRotors;
  ArmValues weights = {1.0, -1.0, 0.0, 0.0, 0.0, 0.0};
  // A described vehicle's mode read (its index in ArmModeHz); -1 the
  // birotor's symmetric mode (SymmetricArmModeHz) or no test [1].
  int mode_index = -1;
  // Whether the mode is read on some of the arms only (an arm without a
  // gauge: GaugedModalWeights); such a reading may hold a bias beyond its
  // noise (arm_mode_partial_gauge_reading_bias).
  bool read_on_some_gauges = false;
  // Per rotor, what a tip-mass error of 100 % (every arm's m_p,i scaled
  // together) puts into its force at hover: d f_i / d r of the hover
  // thrusts (SolveMultiArmHover), which is the error the filter makes on a
  // vehicle whose tip masses are r times the file's (the trirotor: 4.48 /
  // 2.82 / 2.83 N; tip_weight_n on each rotor of the birotor) [N].
  ArmValues rotor_tip_weight_n{};
  static ArmModeExpectation At(double hz) { return {hz, hz, hz, 0.5, 0.0}; }
};
ArmModeExpectation ExpectedArmMode(const BirotorParams& params);
// The same for any described vehicle: its most readable arm mode at hover
// (MostReadableArmMode: the birotor's symmetric mode, the trirotor's 64.6 Hz
// mode of arm 1 against arms 2 and 3) and the combination of the gauges that
// reads it alone (ModalGaugeWeights; largest |weight| 1 on a gauge of scale 1); the range
// allows each gauge scale s_i != 1 to be a stiffness k_i / s_i. With an
// arm without a gauge, the gauges there are read it with the nearest modes
// nulled (GaugedModalWeights). No test (file_hz 0) without a gauge, when
// the modes do not separate, or when the mode does not ring alone in its
// band (ArmModeStandsAlone: the quadrotor; ArmModeLeakSmall: too much of
// another mode in the reading);
// rotor_tip_weight_n is filled then too (what the unconfirmed tip mass puts
// into each force: without a test its prior stays in the sigma in the air).
ArmModeExpectation ExpectedArmMode(const VehicleDescription& vehicle);

// The same while the EKF learns strain scales g_i (learn_strain_scale): a
// learned g_i is a gauge scale (the mode stays) or a stiffness k / g_i (the
// mode moves by g_i^-stiffness_exponent) or anything between, for every g_i
// within two sigma of the learned value. Widens `file` (no allocation).
ArmModeExpectation WithLearnedStrainScales(const ArmModeExpectation& file, const double g[2], const double g_std[2]);

}  // namespace birotor
