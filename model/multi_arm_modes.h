// The arm modes of an N-arm vehicle at hover with their shapes, and the
// combination of the gauges that reads one mode alone: what the arm-mode
// test (estimator/arm_mode_monitor.h) listens to on any described vehicle.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "model/vehicle_description.h"

namespace birotor {

// One oscillatory mode of the hover linearization (model/multi_arm_linearization.h).
struct ArmModeShape {
  double frequency_hz = 0;   // undamped natural frequency |lambda| / 2 pi [Hz]
  double damping_ratio = 0;  // -Re(lambda) / |lambda| [1]
  // The mode's arm deflections b_1 .. b_N (the eigenvector's b rows turned
  // real: rotated so its largest component is real and positive, the
  // imaginary rest of a lightly damped mode dropped), largest |b_i| = 1 [1].
  Eigen::VectorXd deflection;
  // How much the rotors' turbulence rings it: the std of the shape's
  // amplitude a (b = sum_m a_m deflection_m) when each rotor's thrust
  // carries noise of relative intensity 1 (f_i at hover times white noise
  // of unit PSD, filtered as an Ornstein-Uhlenbeck turbulence well above its
  // corner: PSD / omega^2), from the modal form: var = |c|^2 |u^H B
  // diag(f)|^2 / (2 zeta omega^3), u the left and c the b part's scale of
  // the right eigenvector. Relative figure: modes are compared by it [1].
  double turbulence_response = 0;
};

// The oscillatory modes at SolveMultiArmHover's equilibrium, by frequency
// (the frequencies are OscillatoryModes' of the same matrix).
std::vector<ArmModeShape> MultiArmModeShapes(const VehicleDescription& vehicle);

// Row m: the weights w with w^T b the amplitude of mode m alone, b the arm
// deflections (the inverse of S = [deflection_1 .. deflection_N]); the
// rigid body's slow motion is left in it (the arm-mode test band-passes).
// Empty when there are not as many modes as arms or S is near singular
// (reciprocal condition number below 1e-6).
Eigen::MatrixXd ModalGaugeWeights(const std::vector<ArmModeShape>& modes, int arm_count);

// The same for a vehicle whose gauges are on some arms only (gauged[i]; one
// entry per arm, as many modes as arms): row m has w_i = 0 on an arm
// without a gauge, w^T deflection_m = 1 and w^T deflection_j = 0 for the
// (gauges - 1) other modes nearest m in frequency (those the test's
// band-pass lets through most); the modes left are read along with m
// (ArmModeLeakSmall). A row whose modes the gauges cannot separate
// (reciprocal condition number below 1e-6) is zero. Empty without a gauge
// or with another number of modes.
Eigen::MatrixXd GaugedModalWeights(const std::vector<ArmModeShape>& modes, const std::vector<bool>& gauged);

// The mode the gauges read best in flight: the largest ratio of its
// turbulence response's variance to the gauge noise in its combination,
// turbulence_response^2 / sum_i W(m, i)^2 (equal noise on every gauge);
// -1 without weights or when every row is zero (a zero row is not a candidate).
int MostReadableArmMode(const std::vector<ArmModeShape>& modes, const Eigen::MatrixXd& weights);

// Whether mode m rings alone in its band: every other mode within
// band_fraction of its frequency has a turbulence response variance below
// 1 / variance_ratio of m's. A neighbour that rings alike leaks into the
// combination as soon as the flight leaves the hover the weights were
// made for (the quadrotor's 60.8 / 61.7 / 66.7 Hz modes: a matching
// vehicle reads up to +4 %, the test's limit).
bool ArmModeStandsAlone(const std::vector<ArmModeShape>& modes, int m, double band_fraction, double variance_ratio);

// Whether mode m's weights w (a row of GaugedModalWeights) let little of the
// other modes within band_fraction of its frequency through: sum_j (w^T
// deflection_j)^2 turbulence_response_j^2 below 1 / variance_ratio of m's
// variance. Every mode nulled (every arm gauged): 0, always small.
bool ArmModeLeakSmall(const std::vector<ArmModeShape>& modes, const Eigen::RowVectorXd& w, int m, double band_fraction,
                      double variance_ratio);

}  // namespace birotor
