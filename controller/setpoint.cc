#include "samples/setpoint.h"

#include <cmath>

#include "controller/reference_point.h"

namespace birotor {
namespace {

double OrZero(double value) { return std::isnan(value) ? 0.0 : value; }

}  // namespace

Setpoint SetpointFromReference(const ReferencePoint& reference, int64_t utime, int32_t seq) {
  Setpoint s;
  s.utime = utime;
  s.seq = seq;
  s.x_m = reference.position_m.x();
  s.z_m = reference.position_m.y();
  s.x_dot_m_s = reference.velocity_m_s.x();
  s.z_dot_m_s = reference.velocity_m_s.y();
  s.x_ddot_m_s2 = reference.acceleration_m_s2.x();
  s.z_ddot_m_s2 = reference.acceleration_m_s2.y();
  return s;
}

ReferencePoint ReferenceFromSetpoint(const Setpoint& setpoint, double dt_s) {
  ReferencePoint r;
  const Eigen::Vector2d v(OrZero(setpoint.x_dot_m_s), OrZero(setpoint.z_dot_m_s));
  const Eigen::Vector2d a(OrZero(setpoint.x_ddot_m_s2), OrZero(setpoint.z_ddot_m_s2));
  r.position_m = Eigen::Vector2d(setpoint.x_m, setpoint.z_m) + dt_s * v + 0.5 * dt_s * dt_s * a;
  r.velocity_m_s = v + dt_s * a;
  r.acceleration_m_s2 = a;
  return r;
}

}  // namespace birotor
