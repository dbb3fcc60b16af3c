// Counted messages: the count check, the birotor twins through the field
// lists of message_fields.h, and the vehicle description on the wire.
#include "transport/counted_messages.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <type_traits>
#include <vector>

#include "model/vehicle_description_checksum.h"
#include "transport/message_fields.h"

namespace birotor {
namespace {

// The count of a counted message, the lengths of its counted arrays, and its
// per-rotor fault bits (0 where the type has none).
struct Shape {
  int count = 0;
  std::array<size_t, 12> lengths{};  // [0, arrays): one per counted array (vehicle_description_t has 12)
  size_t arrays = 0;
  int32_t fault_bits = 0;
};

Shape ShapeOf(int count, std::initializer_list<size_t> lengths, int32_t fault_bits = 0) {
  Shape shape;
  shape.count = count;
  for (size_t length : lengths) shape.lengths[shape.arrays++] = length;
  shape.fault_bits = fault_bits;
  return shape;
}

Shape ShapeOf(const strain_n_t& m) { return ShapeOf(m.n_arms, {m.deflection_rad.size()}); }
Shape ShapeOf(const motor_n_t& m) { return ShapeOf(m.n_rotors, {m.omega_cmd_rad_s.size(), m.omega_meas_rad_s.size()}); }
Shape ShapeOf(const loadcell_n_t& m) { return ShapeOf(m.n_rotors, {m.force_n.size()}); }
Shape ShapeOf(const truth_n_t& m) {
  return ShapeOf(m.n_arms, {m.deflection_rad.size(), m.deflection_dot_rad_s.size(), m.omega_rad_s.size(),
                            m.force_n.size(), m.thrust_scale.size()});
}
Shape ShapeOf(const force_estimate_n_t& m) {
  return ShapeOf(m.n_rotors, {m.force_n.size(), m.force_std_n.size(), m.thrust_scale.size()}, m.rotor_fault_bits);
}
Shape ShapeOf(const motor_command_n_t& m) { return ShapeOf(m.n_rotors, {m.omega_cmd_rad_s.size()}); }

CountCheck Check(const Shape& shape, int expected_count) {
  if (shape.count < kBirotorArmCount || shape.count > kMaxArms) return CountCheck::kOutOfRange;
  const size_t count = static_cast<size_t>(shape.count);
  for (size_t i = 0; i < shape.arrays; ++i) {
    if (shape.lengths[i] != count) return CountCheck::kInconsistent;
  }
  if ((static_cast<uint32_t>(shape.fault_bits) >> count) != 0) return CountCheck::kInconsistent;
  return shape.count == expected_count ? CountCheck::kMatches : CountCheck::kMismatch;
}

// Birotor -> counted with N = 2 through the type's field list.
template <class Counted, class Birotor>
Counted ToCounted(const Birotor& message, int8_t Counted::*count, void (*copy)(const Birotor&, Counted*)) {
  Counted out{};
  out.*count = kBirotorArmCount;
  copy(message, &out);
  return out;
}

// Counted -> birotor through the type's field list, only for a consistent N = 2.
template <class Counted, class Birotor>
bool ToBirotor(const Counted& message, Birotor* out, void (*copy)(const Counted&, Birotor*)) {
  if (Check(ShapeOf(message), kBirotorArmCount) != CountCheck::kMatches) return false;
  Birotor converted{};
  copy(message, &converted);
  *out = converted;
  return true;
}

// force_estimate_t's two rotor bits <-> rotor_fault_bits 0 and 1.
constexpr int32_t kBirotorRotorFaultBits =
    force_estimate_t::STATUS_ROTOR1_FAULT | force_estimate_t::STATUS_ROTOR2_FAULT;

int32_t RotorFaultBits(int32_t birotor_status) {
  return ((birotor_status & force_estimate_t::STATUS_ROTOR1_FAULT) ? force_estimate_n_t::ROTOR_FAULT_ROTOR1 : 0) |
         ((birotor_status & force_estimate_t::STATUS_ROTOR2_FAULT) ? force_estimate_n_t::ROTOR_FAULT_ROTOR2 : 0);
}

int32_t BirotorStatus(int32_t status, int32_t rotor_fault_bits) {
  return (status & ~kBirotorRotorFaultBits) |
         ((rotor_fault_bits & force_estimate_n_t::ROTOR_FAULT_ROTOR1) ? force_estimate_t::STATUS_ROTOR1_FAULT : 0) |
         ((rotor_fault_bits & force_estimate_n_t::ROTOR_FAULT_ROTOR2) ? force_estimate_t::STATUS_ROTOR2_FAULT : 0);
}

// The one field list of vehicle_description_t, both ways: assign(field of
// the description, the message's field) for the body, and with the arm
// index i for the per-arm arrays. Description and message are const on the
// side that is read.
template <class Description, class Message, class Assign>
void VisitBodyFields(Description& d, Message& m, Assign assign) {
  assign(d.body_mass_kg, m.body_mass_kg);
  assign(d.body_inertia_kg_m2, m.body_inertia_kg_m2);
  assign(d.gravity_m_s2, m.gravity_m_s2);
  assign(d.omega_max_rad_s, m.omega_max_rad_s);
  assign(d.turbulence_std, m.turbulence_std);
  assign(d.turbulence_corr_time_s, m.turbulence_corr_time_s);
  assign(d.gauge_offset_std_rad, m.gauge_offset_std_rad);
  assign(d.gauge_drift_psd_rad2_s, m.gauge_drift_psd_rad2_s);
}

template <class Arm, class Message, class Assign>
void VisitArmFields(Arm& arm, Message& m, size_t i, Assign assign) {
  assign(arm.angle_rad, m.angle_rad, i);
  assign(arm.length_m, m.length_m, i);
  assign(arm.thrust_angle_rad, m.thrust_angle_rad, i);
  assign(arm.spin, m.spin, i);
  assign(arm.stiffness_n_m_rad, m.stiffness_n_m_rad, i);
  assign(arm.damping_n_m_s_rad, m.damping_n_m_s_rad, i);
  assign(arm.tip_mass_kg, m.tip_mass_kg, i);
  assign(arm.thrust_coeff_n_s2_rad2, m.thrust_coeff_n_s2_rad2, i);
  assign(arm.motor_time_constant_s, m.motor_time_constant_s, i);
  assign(arm.has_gauge, m.has_gauge, i);
  assign(arm.gauge_scale, m.gauge_scale, i);
  assign(arm.gauge_offset_rad, m.gauge_offset_rad, i);
}

Shape ShapeOf(const vehicle_description_t& m) {
  Shape shape = ShapeOf(m.n_arms, {});
  const ArmDescription unused;
  VisitArmFields(unused, m, 0,
                 [&shape](const auto&, const auto& array, size_t) { shape.lengths[shape.arrays++] = array.size(); });
  return shape;
}

}  // namespace

const char* CountCheckName(CountCheck check) {
  switch (check) {
    case CountCheck::kMatches:
      return "matches";
    case CountCheck::kOutOfRange:
      return "out_of_range";
    case CountCheck::kMismatch:
      return "mismatch";
    case CountCheck::kInconsistent:
      return "inconsistent";
  }
  return "unknown";
}

void CountRefusals::Count(CountCheck check) {
  switch (check) {
    case CountCheck::kMatches:
      break;
    case CountCheck::kOutOfRange:
      ++out_of_range;
      break;
    case CountCheck::kMismatch:
      ++mismatch;
      break;
    case CountCheck::kInconsistent:
      ++inconsistent;
      break;
  }
}

CountCheck CheckCount(const strain_n_t& m, const VehicleDescription& d) { return Check(ShapeOf(m), d.arm_count); }
CountCheck CheckCount(const motor_n_t& m, const VehicleDescription& d) { return Check(ShapeOf(m), d.arm_count); }
CountCheck CheckCount(const loadcell_n_t& m, const VehicleDescription& d) { return Check(ShapeOf(m), d.arm_count); }
CountCheck CheckCount(const truth_n_t& m, const VehicleDescription& d) { return Check(ShapeOf(m), d.arm_count); }
CountCheck CheckCount(const force_estimate_n_t& m, const VehicleDescription& d) {
  return Check(ShapeOf(m), d.arm_count);
}
CountCheck CheckCount(const motor_command_n_t& m, const VehicleDescription& d) {
  return Check(ShapeOf(m), d.arm_count);
}

strain_n_t ToCountedMessage(const strain_t& m) { return ToCounted(m, &strain_n_t::n_arms, internal::CopyStrainFields); }

motor_n_t ToCountedMessage(const motor_t& m) { return ToCounted(m, &motor_n_t::n_rotors, internal::CopyMotorFields); }

loadcell_n_t ToCountedMessage(const loadcell_t& m) {
  return ToCounted(m, &loadcell_n_t::n_rotors, internal::CopyLoadCellFields);
}

truth_n_t ToCountedMessage(const truth_t& m) { return ToCounted(m, &truth_n_t::n_arms, internal::CopyTruthFields); }

force_estimate_n_t ToCountedMessage(const force_estimate_t& m) {
  force_estimate_n_t out = ToCounted(m, &force_estimate_n_t::n_rotors, internal::CopyForceFields);
  out.status = m.status & ~kBirotorRotorFaultBits;
  out.rotor_fault_bits = RotorFaultBits(m.status);
  return out;
}

motor_command_n_t ToCountedMessage(const motor_command_t& m) {
  return ToCounted(m, &motor_command_n_t::n_rotors, internal::CopyMotorCommandFields);
}

bool ToBirotorMessage(const strain_n_t& m, strain_t* out) { return ToBirotor(m, out, internal::CopyStrainFields); }
bool ToBirotorMessage(const motor_n_t& m, motor_t* out) { return ToBirotor(m, out, internal::CopyMotorFields); }
bool ToBirotorMessage(const loadcell_n_t& m, loadcell_t* out) {
  return ToBirotor(m, out, internal::CopyLoadCellFields);
}
bool ToBirotorMessage(const truth_n_t& m, truth_t* out) { return ToBirotor(m, out, internal::CopyTruthFields); }
bool ToBirotorMessage(const motor_command_n_t& m, motor_command_t* out) {
  return ToBirotor(m, out, internal::CopyMotorCommandFields);
}
bool ToBirotorMessage(const force_estimate_n_t& m, force_estimate_t* out) {
  if (!ToBirotor(m, out, internal::CopyForceFields)) return false;
  out->status = BirotorStatus(m.status, m.rotor_fault_bits);
  return true;
}

namespace {
std::vector<double> FirstEntries(const ArmValues& values, int count) {
  return std::vector<double>(values.begin(), values.begin() + std::clamp(count, 0, kMaxSampleArms));
}
}  // namespace

strain_n_t ToMessage(const MultiArmStrainSample& s) {
  strain_n_t m{};
  m.utime = s.utime;
  m.seq = s.seq;
  m.n_arms = static_cast<int8_t>(s.n_arms);
  m.deflection_rad = FirstEntries(s.deflection_rad, s.n_arms);
  return m;
}

motor_n_t ToMessage(const MultiArmMotorSample& s) {
  motor_n_t m{};
  m.utime = s.utime;
  m.seq = s.seq;
  m.n_rotors = static_cast<int8_t>(s.n_rotors);
  m.omega_cmd_rad_s = FirstEntries(s.omega_cmd_rad_s, s.n_rotors);
  m.omega_meas_rad_s = FirstEntries(s.omega_meas_rad_s, s.n_rotors);
  return m;
}

loadcell_n_t ToMessage(const MultiArmLoadCellSample& s) {
  loadcell_n_t m{};
  m.utime = s.utime;
  m.seq = s.seq;
  m.n_rotors = static_cast<int8_t>(s.n_rotors);
  m.force_n = FirstEntries(s.force_n, s.n_rotors);
  return m;
}

truth_n_t ToMessage(const MultiArmTruthSample& s) {
  truth_n_t m{};
  m.utime = s.utime;
  m.x_m = s.x_m;
  m.z_m = s.z_m;
  m.phi_rad = s.phi_rad;
  m.n_arms = static_cast<int8_t>(s.n_arms);
  m.deflection_rad = FirstEntries(s.deflection_rad, s.n_arms);
  m.x_dot_m_s = s.x_dot_m_s;
  m.z_dot_m_s = s.z_dot_m_s;
  m.phi_dot_rad_s = s.phi_dot_rad_s;
  m.deflection_dot_rad_s = FirstEntries(s.deflection_dot_rad_s, s.n_arms);
  m.omega_rad_s = FirstEntries(s.omega_rad_s, s.n_arms);
  m.force_n = FirstEntries(s.force_n, s.n_arms);
  m.thrust_scale = FirstEntries(s.thrust_scale, s.n_arms);
  return m;
}

force_estimate_n_t ToMessage(const MultiArmForceEstimate& e) {
  force_estimate_n_t m{};
  ToMessage(e, &m);
  return m;
}

namespace {

// Entries [0, n) of a sample's array into a message's vector, reusing its storage.
template <class Array>
void AssignFirst(const Array& from, int n, std::vector<double>* to) {
  to->assign(from.begin(), from.begin() + std::clamp(n, 0, static_cast<int>(from.size())));
}

// Entries [0, min(count, kMaxSampleArms)) of a counted array into a sample's.
template <class Array>
void CopyFirst(const std::vector<double>& from, int count, Array* to) {
  const size_t n = std::min<size_t>(static_cast<size_t>(std::max(count, 0)), std::min(from.size(), to->size()));
  std::copy_n(from.begin(), n, to->begin());
}

}  // namespace

void ToMessage(const MultiArmForceEstimate& e, force_estimate_n_t* m) {
  m->utime = e.utime;
  m->seq = e.seq;
  m->n_rotors = static_cast<int8_t>(e.n_rotors);
  AssignFirst(e.force_n, e.n_rotors, &m->force_n);
  AssignFirst(e.force_std_n, e.n_rotors, &m->force_std_n);
  AssignFirst(e.thrust_scale, e.n_rotors, &m->thrust_scale);
  m->status = e.status;  // composed in estimator/force_status.cc: a copy
  m->rotor_fault_bits = e.rotor_fault_bits;
}

void FromMessage(const strain_n_t& m, MultiArmStrainSample* s) {
  *s = MultiArmStrainSample();
  s->utime = m.utime;
  s->seq = m.seq;
  s->n_arms = m.n_arms;
  CopyFirst(m.deflection_rad, m.n_arms, &s->deflection_rad);
}

void FromMessage(const loadcell_n_t& m, MultiArmLoadCellSample* s) {
  *s = MultiArmLoadCellSample();
  s->utime = m.utime;
  s->seq = m.seq;
  s->n_rotors = m.n_rotors;
  CopyFirst(m.force_n, m.n_rotors, &s->force_n);
}

void FromMessage(const truth_n_t& m, MultiArmTruthSample* s) {
  *s = MultiArmTruthSample();
  s->utime = m.utime;
  s->x_m = m.x_m;
  s->z_m = m.z_m;
  s->phi_rad = m.phi_rad;
  s->n_arms = m.n_arms;
  CopyFirst(m.deflection_rad, m.n_arms, &s->deflection_rad);
  s->x_dot_m_s = m.x_dot_m_s;
  s->z_dot_m_s = m.z_dot_m_s;
  s->phi_dot_rad_s = m.phi_dot_rad_s;
  CopyFirst(m.deflection_dot_rad_s, m.n_arms, &s->deflection_dot_rad_s);
  CopyFirst(m.omega_rad_s, m.n_arms, &s->omega_rad_s);
  CopyFirst(m.force_n, m.n_arms, &s->force_n);
  CopyFirst(m.thrust_scale, m.n_arms, &s->thrust_scale);
}

void FromMessage(const force_estimate_n_t& m, MultiArmForceEstimate* e) {
  *e = MultiArmForceEstimate();
  e->utime = m.utime;
  e->seq = m.seq;
  e->n_rotors = m.n_rotors;
  CopyFirst(m.force_n, m.n_rotors, &e->force_n);
  CopyFirst(m.force_std_n, m.n_rotors, &e->force_std_n);
  CopyFirst(m.thrust_scale, m.n_rotors, &e->thrust_scale);
  e->status = m.status;
  e->rotor_fault_bits = m.rotor_fault_bits;
}

void FromMessage(const motor_n_t& m, MultiArmMotorSample* s) {
  *s = MultiArmMotorSample();
  s->utime = m.utime;
  s->seq = m.seq;
  s->n_rotors = m.n_rotors;
  CopyFirst(m.omega_cmd_rad_s, m.n_rotors, &s->omega_cmd_rad_s);
  CopyFirst(m.omega_meas_rad_s, m.n_rotors, &s->omega_meas_rad_s);
}

vehicle_description_t ToMessage(const VehicleDescription& description, const std::string& publisher) {
  vehicle_description_t m{};
  m.publisher = publisher;
  m.name = description.name;
  m.checksum = DescriptionChecksum(description);
  VisitBodyFields(description, m, [](const double& from, double& to) { to = from; });
  m.n_arms = static_cast<int8_t>(description.arm_count);
  for (size_t i = 0; i < static_cast<size_t>(std::clamp(description.arm_count, 0, kMaxArms)); ++i) {
    VisitArmFields(description.arms[i], m, i, [](const auto& from, auto& array, size_t) {
      array.push_back(static_cast<typename std::decay_t<decltype(array)>::value_type>(from));
    });
  }
  return m;
}

bool FromMessage(const vehicle_description_t& m, VehicleDescription* out, std::string* why) {
  const CountCheck shape = Check(ShapeOf(m), m.n_arms);
  if (shape != CountCheck::kMatches) {
    *why = std::string("vehicle_description_t: n_arms ") + std::to_string(m.n_arms) + ": " + CountCheckName(shape);
    return false;
  }
  VehicleDescription d;
  d.name = m.name;
  d.arm_count = m.n_arms;
  VisitBodyFields(d, m, [](double& to, const double& from) { to = from; });
  for (size_t i = 0; i < static_cast<size_t>(d.arm_count); ++i) {
    VisitArmFields(d.arms[i], m, i, [](auto& to, const auto& array, size_t index) {
      to = static_cast<std::decay_t<decltype(to)>>(array[index]);
    });
  }
  const std::string checksum = DescriptionChecksum(d);
  if (checksum != m.checksum) {
    *why = "vehicle_description_t: checksum " + m.checksum + " is not the one of its fields (" + checksum + ")";
    return false;
  }
  *out = d;
  return true;
}

}  // namespace birotor
