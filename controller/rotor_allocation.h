// From the law's total thrust and thrust difference to the two rotors within
// what they can make, keeping attitude before altitude (issue 25): the
// difference f2 - f1 (the pitch torque, tau = L (f2 - f1), eq. 3.12) is kept
// and the total moved into the range both rotors can still make; only when
// the difference alone is beyond reach is it clipped too. Pure.
#pragma once

namespace birotor {

struct RotorAllocation {
  double force_n[2] = {0.0, 0.0};   // rotor 1, 2 [N], each within [0, max_force_n[i]]
  bool total_limited = false;       // the total was moved (altitude gives way)
  bool difference_limited = false;  // the difference was clipped (attitude gives way)
};

// f1 = (F - D) / 2, f2 = (F + D) / 2 with 0 <= f_i <= max_force_n[i]:
// D clipped to [-2 max1, 2 max2] first, then F to [|D|, min(2 max1 + D, 2 max2 - D)].
RotorAllocation AllocateAttitudeFirst(double total_force_n, double force_difference_n, const double (&max_force_n)[2]);

}  // namespace birotor
