// Whether a flight kept its vehicle, said in one line: the one definition that
// the demo, birotor-sim --controller, birotor-eval --control and
// birotor-review share. A flight is lost when the vehicle fell far below where
// it was meant to be, when its attitude is gone, or when it hit the ground
// hard; a script reads the first word ("kept" or "LOST").
#pragma once

#include <cstdint>
#include <string>

namespace birotor {

struct FlightVerdictOptions {
  // Below the reference altitude (the setpoint, else the first sample's
  // altitude) by this much: lost. The controller cases' "crashed" [m].
  double lost_altitude_loss_m = 0.5;
  // |phi| beyond this: the attitude is lost (the controllers limit the tilt to
  // 0.5 rad; 1.0 is a tumble, not a manoeuvre) [rad].
  double lost_tilt_rad = 1.0;
  // Arriving on the ground faster than this: a ground hit, not a landing
  // (the controlled descent's target is 1 m/s) [m/s].
  double ground_hit_speed_m_s = 2.0;
};

// What the judge saw; times are seconds on the caller's axis.
struct FlightVerdict {
  bool lost = false;
  int64_t samples = 0;
  double max_altitude_loss_m = 0;  // max(z_ref - z, 0) [m]
  double altitude_loss_at_s = 0;
  double max_tilt_rad = 0;  // max |phi| [rad]
  double tilt_at_s = 0;
  bool ground_hit = false;          // arrived on the ground faster than ground_hit_speed_m_s
  double ground_speed_m_s = 0;      // sink rate at the first ground contact; 0 without one [m/s]
  double ground_contact_at_s = -1;  // first contact; -1 without one

  // "kept: altitude loss 0.014 m, max tilt 0.12 rad" or "LOST: altitude loss
  // 28.6 m at t = 3.20 s; tilt 1.90 rad at t = 3.50 s; ground hit at 6.1 m/s".
  std::string Line() const;
};

// Feed one sample at a time (no allocation), then Result().
class FlightJudge {
 public:
  explicit FlightJudge(const FlightVerdictOptions& options = {}) : options_(options) {}
  // z_reference_m: NaN when not known (then the first sample's altitude);
  // ground_z_m: NaN when no ground is known (then no contact is judged).
  void Add(double t_s, double z_m, double z_reference_m, double phi_rad, double z_dot_m_s, double ground_z_m);
  FlightVerdict Result() const;

 private:
  FlightVerdictOptions options_;
  FlightVerdict verdict_;
  double first_z_m_ = 0;
  bool was_above_ground_ = true;
};

}  // namespace birotor
