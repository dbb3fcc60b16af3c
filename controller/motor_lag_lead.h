// One rotor's lead of its motor lag, shared by both cascades
// (VehicleController, MultiArmController; docs/controller.md, "Thrust
// lead"). The rotor follows its command with the first-order lag tau_m
// (model/plant.h); the command leads it:
//  - the allocated thrust's change at this period's efficiency e [1]
//    through omega (thrust_lead_s s + 1) / (thrust_lead_filter_s s + 1):
//    the law then sees a rotor lagging thrust_lead_filter_s instead of
//    tau_m, and the noise the lead amplifies is bounded by their ratio;
//  - while e falls, + motor_lead_s x d(omega)/dt, d(omega)/dt =
//    -omega / (2 e) de/dt, the speed omega = sqrt(f / (e c_T)) a falling e
//    needs (a rising e is not led: the estimate rings upwards right after a
//    loss, and a lead on that would cut the weak rotor when it is needed).
// Two doubles and a count of state; no allocation.
#ifndef BIROTOR_CONTROLLER_MOTOR_LAG_LEAD_H_
#define BIROTOR_CONTROLLER_MOTOR_LAG_LEAD_H_

#include <limits>

#include "controller/controller_params.h"

namespace birotor {

// A rotor's map: f = e c_T omega^2 within [0, omega_max].
struct RotorMap {
  double thrust_coeff_n_s2_rad2 = 0.0;  // c_T [N s^2/rad^2]
  double omega_max_rad_s = 0.0;         // [rad/s]
};

class MotorLagLead {
 public:
  // The led speed [rad/s] for omega_rad_s, the speed the command gives for
  // force_n [N] at efficiency [1] this period (dt_s [s] after the last);
  // remembers force_n and efficiency for the next period. Not clipped: the
  // caller keeps it within [0, omega_max]. A rotor not driven (omega not
  // finite, e <= 0) or a period without time (dt_s <= 0) is not led, and
  // the former forgets its filtered lead.
  double Lead(const EfficiencyParams& params, const RotorMap& map, double omega_rad_s, double force_n,
              double efficiency, double dt_s);

 private:
  double last_force_n_ = std::numeric_limits<double>::quiet_NaN();  // the thrust of the period before [N]
  double last_efficiency_ = 1.0;                                    // e of the period before [1]
  double filtered_lead_rad_s_ = 0.0;                                // the thrust's lead, low-passed [rad/s]
};

}  // namespace birotor

#endif  // BIROTOR_CONTROLLER_MOTOR_LAG_LEAD_H_
