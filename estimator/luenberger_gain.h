// Gain of the discrete Luenberger observer on the linear force model by pole
// placement (thesis section 5.4.2, eq. 5.3-5.8, made to work). The observer
// runs in filter form: x+ = A_d x, then the gyro x = x+ + L_g (y_g - C_g x+),
// then the strain gauges x = x + L (y - C x), so its error obeys
//   e[k+1] = (I - L C) (I - L_g C_g) A_d e[k]
// and L, L_g place its eigenvalues. L acts on the six strain-observable
// states only and L_g on phi_dot only: the error matrix is block triangular,
// the forces are estimated from the strain gauges alone (the thesis's
// observer), and the gyro only keeps the phi_dot error from drifting.
#pragma once

#include <array>
#include <complex>

#include "estimator/estimator_config.h"
#include "estimator/linear_force_model.h"

namespace birotor {

struct ObserverGains {
  LinearGain strain;    // L [rad/rad, (rad/s)/rad, N/rad]
  LinearGyroGain gyro;  // L_g: phi_dot row only [1]
};

// Discrete poles the design places: per channel (b_s = b1 + b2 with f1 - f2,
// then b_d = b1 - b2 with f1 + f2) the arm pair exp(s T), s = w_n (-zeta +- j
// sqrt(1 - zeta^2)) with w_n the channel's own arm frequency, and the force
// pole exp(-2 pi force_bandwidth_hz T); last, the phi_dot pole, the same as
// the force pole.
std::array<std::complex<double>, kLinearStateSize> DesiredObserverPoles(const LinearForceModel& model,
                                                                        const LuenbergerOptions& options);

// L and L_g. The symmetric vehicle decouples into the two 3-state channels
// above (mirror symmetry of hover); in each, on the scaled states, Ackermann's
// formula for the pair (A_j, C_j A_j):
//   L_j = phi(A_j) [C_j A_j; C_j A_j^2; C_j A_j^3]^-1 e_3,
// phi the polynomial with the desired poles. Throws std::invalid_argument if
// the channels do not decouple or the options are out of range.
ObserverGains PlaceObserverPoles(const LinearForceModel& model, const LuenbergerOptions& options);

// The error matrix (I - L C) (I - L_g C_g) A_d (for the stability check).
LinearMatrix ObserverErrorMatrix(const LinearForceModel& model, const ObserverGains& gains);

}  // namespace birotor
