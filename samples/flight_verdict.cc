#include "samples/flight_verdict.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace birotor {

namespace {
// A body within this of the ground is on it [m].
constexpr double kContactToleranceM = 1e-3;
}  // namespace

void FlightJudge::Add(double t_s, double z_m, double z_reference_m, double phi_rad, double z_dot_m_s,
                      double ground_z_m) {
  if (!std::isfinite(z_m) || !std::isfinite(phi_rad)) return;  // a gap in the track, not a verdict
  if (verdict_.samples == 0) first_z_m_ = z_m;
  ++verdict_.samples;
  const double reference_m = std::isfinite(z_reference_m) ? z_reference_m : first_z_m_;
  const double loss_m = reference_m - z_m;
  const bool landed_before = verdict_.ground_contact_at_s >= 0 && !verdict_.ground_hit;
  if (!landed_before && loss_m > verdict_.max_altitude_loss_m) {
    verdict_.max_altitude_loss_m = loss_m;
    verdict_.altitude_loss_at_s = t_s;
  }
  if (std::fabs(phi_rad) > verdict_.max_tilt_rad) {
    verdict_.max_tilt_rad = std::fabs(phi_rad);
    verdict_.tilt_at_s = t_s;
  }
  if (std::isfinite(ground_z_m)) {
    const bool on_ground = z_m <= ground_z_m + kContactToleranceM;
    if (on_ground && was_above_ground_ && verdict_.ground_contact_at_s < 0 && verdict_.samples > 1) {
      verdict_.ground_contact_at_s = t_s;
      verdict_.ground_speed_m_s = std::isfinite(z_dot_m_s) ? std::max(-z_dot_m_s, 0.0) : 0.0;
      verdict_.ground_hit = verdict_.ground_speed_m_s > options_.ground_hit_speed_m_s;
    }
    was_above_ground_ = !on_ground;
  }
  // A soft landing (a controlled descent after a loss the rotors cannot hover
  // with) ends the altitude judgement: below the reference is then expected.
  const bool landed = verdict_.ground_contact_at_s >= 0 && !verdict_.ground_hit;
  verdict_.lost = (verdict_.max_altitude_loss_m >= options_.lost_altitude_loss_m && !landed) ||
                  verdict_.max_tilt_rad > options_.lost_tilt_rad || verdict_.ground_hit;
}

FlightVerdict FlightJudge::Result() const { return verdict_; }

std::string FlightVerdict::Line() const {
  char text[256];
  if (samples == 0) return "unknown: no position in the log";
  if (!lost) {
    std::snprintf(text, sizeof(text), "kept: altitude loss %.3f m, max tilt %.2f rad", max_altitude_loss_m,
                  max_tilt_rad);
    std::string out = text;
    if (ground_contact_at_s >= 0) {
      std::snprintf(text, sizeof(text), "; landed at %.2f m/s, t = %.2f s", ground_speed_m_s, ground_contact_at_s);
      out += text;
    }
    return out;
  }
  std::string out = "LOST:";
  std::snprintf(text, sizeof(text), " altitude loss %.3f m at t = %.2f s;", max_altitude_loss_m, altitude_loss_at_s);
  out += text;
  std::snprintf(text, sizeof(text), " max tilt %.2f rad at t = %.2f s", max_tilt_rad, tilt_at_s);
  out += text;
  if (ground_hit) {
    std::snprintf(text, sizeof(text), "; ground hit at %.1f m/s, t = %.2f s", ground_speed_m_s, ground_contact_at_s);
    out += text;
  }
  return out;
}

}  // namespace birotor
