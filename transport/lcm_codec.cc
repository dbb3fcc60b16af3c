// Non-template parts of the checked LCM codec.
#include "transport/lcm_codec.h"

#include <initializer_list>

namespace birotor {

const char* DecodeErrorName(DecodeError error) {
  switch (error) {
    case DecodeError::kNone:
      return "none";
    case DecodeError::kTruncated:
      return "truncated";
    case DecodeError::kBadFingerprint:
      return "bad_fingerprint";
    case DecodeError::kMalformed:
      return "malformed";
  }
  return "unknown";
}

namespace internal {

uint64_t ReadFingerprint(const void* data) {
  const auto* bytes = static_cast<const uint8_t*>(data);
  uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value = (value << 8) | bytes[i];
  return value;
}

namespace {

// Reads the big-endian wire layout of lcm_coretypes.h, never past the end.
class WireCursor {
 public:
  WireCursor(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  bool Skip(size_t bytes) {
    if (bytes > size_ - pos_) return Fail(DecodeError::kTruncated);
    pos_ += bytes;
    return true;
  }

  bool ReadInt32(int32_t* value) {
    if (4 > size_ - pos_) return Fail(DecodeError::kTruncated);
    uint32_t raw = 0;
    for (int i = 0; i < 4; ++i) raw = (raw << 8) | data_[pos_ + i];
    *value = static_cast<int32_t>(raw);
    pos_ += 4;
    return true;
  }

  bool ReadInt8(int8_t* value) {
    if (1 > size_ - pos_) return Fail(DecodeError::kTruncated);
    *value = static_cast<int8_t>(data_[pos_]);
    pos_ += 1;
    return true;
  }

  // LCM string: int32 length including the terminating NUL, then the bytes.
  bool SkipString() {
    int32_t length = 0;
    if (!ReadInt32(&length)) return false;
    if (length < 1) return Fail(DecodeError::kMalformed);
    if (!Skip(static_cast<size_t>(length))) return false;
    // The generated decoder drops the last byte unchecked; it must be the NUL.
    if (data_[pos_ - 1] != '\0') return Fail(DecodeError::kMalformed);
    return true;
  }

  bool Fail(DecodeError error) {
    error_ = error;
    return false;
  }

  DecodeError error() const { return error_; }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  DecodeError error_ = DecodeError::kNone;
};

// Field layout of lcmtypes/input_health_t.lcm.
bool SkipInputHealth(WireCursor* cursor) {
  constexpr size_t kInt64Counters = 11;  // received .. reading_missing
  constexpr size_t kDoubles = 2;         // age_s, rate_hz
  constexpr size_t kTailInt64 = 3;       // not_fused, time_outliers, conflicts
  constexpr size_t kTailInt8 = 1;        // conflict_active
  constexpr size_t kTailDoubles = 3;     // nis_mean, nis_max, gate
  return cursor->SkipString() &&
         cursor->Skip(8 * kInt64Counters + 8 * kDoubles + 8 * kTailInt64 + kTailInt8 + 8 * kTailDoubles);
}

// One step of a wire layout after the fingerprint: fixed bytes, the int8_t
// count, an array of count elements of the given size, or a string.
struct LayoutStep {
  enum Kind { kBytes, kCount, kArray, kString } kind;
  size_t bytes;  // kBytes: how many; kArray: per element
};
constexpr LayoutStep Bytes(size_t bytes) { return {LayoutStep::kBytes, bytes}; }
constexpr LayoutStep Count() { return {LayoutStep::kCount, 0}; }
constexpr LayoutStep Array(size_t element_bytes) { return {LayoutStep::kArray, element_bytes}; }
constexpr LayoutStep String() { return {LayoutStep::kString, 0}; }
constexpr LayoutStep kDoubles = Array(8);
constexpr LayoutStep kInt8s = Array(1);  // int8_t and boolean
constexpr size_t kUtimeSeq = 8 + 4;
// A sealed twin (<type>_auth_t): publisher and counter before the nested
// message (which has no fingerprint of its own), the tag after it.
constexpr LayoutStep kSealHeader = Bytes(8 + 8);
constexpr LayoutStep kSealTag = Bytes(32);

// Walks a counted type's layout: a negative count is malformed (the
// generated decoder would resize a vector to ~2^64 elements), any step past
// the end truncated.
DecodeError WalkLayout(const uint8_t* data, size_t size, std::initializer_list<LayoutStep> steps) {
  WireCursor cursor(data, size);
  if (!cursor.Skip(8)) return cursor.error();  // fingerprint
  int8_t count = 0;
  for (const LayoutStep& step : steps) {
    bool ok = true;
    switch (step.kind) {
      case LayoutStep::kBytes:
        ok = cursor.Skip(step.bytes);
        break;
      case LayoutStep::kCount:
        ok = cursor.ReadInt8(&count) && (count >= 0 || cursor.Fail(DecodeError::kMalformed));
        break;
      case LayoutStep::kArray:
        ok = cursor.Skip(step.bytes * static_cast<size_t>(count));
        break;
      case LayoutStep::kString:
        ok = cursor.SkipString();
        break;
    }
    if (!ok) return cursor.error();
  }
  return DecodeError::kNone;
}

}  // namespace

template <>
DecodeError CheckLengthFields<input_health_t>(const uint8_t* data, size_t size) {
  WireCursor cursor(data, size);
  const bool ok = cursor.Skip(8) && SkipInputHealth(&cursor);  // fingerprint, fields
  return ok ? DecodeError::kNone : cursor.error();
}

// Field layout of lcmtypes/estimator_status_t.lcm.
template <>
DecodeError CheckLengthFields<estimator_status_t>(const uint8_t* data, size_t size) {
  WireCursor cursor(data, size);
  int32_t num_inputs = 0;
  const bool ok = cursor.Skip(8)             // fingerprint
                  && cursor.Skip(8 + 8 + 4)  // utime, wall_utime, seq
                  && cursor.SkipString()     // method
                  && cursor.Skip(4)          // status
                  && cursor.ReadInt32(&num_inputs) && (num_inputs >= 0 || cursor.Fail(DecodeError::kMalformed));
  if (!ok) return cursor.error();
  // Each element consumes bytes, so a huge count fails on the data, not on memory.
  for (int32_t i = 0; i < num_inputs; ++i) {
    if (!SkipInputHealth(&cursor)) return cursor.error();
  }
  const bool tail_ok = cursor.Skip(6 * 8)             // nis mean/max/gate, processing times
                       && cursor.Skip(8)              // resets
                       && cursor.SkipString()         // last_reset_reason
                       && cursor.Skip(8)              // published
                       && cursor.Skip(2 * 8 + 2 * 8)  // force_n, thrust_scale
                       && cursor.Skip(2 * 8 + 2 * 8)  // gauge_offset_rad, gauge_offset_std_rad
                       && cursor.SkipString()         // gauge_offset_source
                       && cursor.Skip(4 * 8)          // tares, tares_refused_*
                       && cursor.SkipString()         // last_tare_refusal
                       && cursor.Skip(4 * 8)          // udp_datagrams .. udp_kernel_dropped
                       && SkipInputHealth(&cursor)    // accelerometer
                       && cursor.Skip(8)              // foreign_force
                       && cursor.Skip(8)              // model_consistency_statistic
                       && cursor.SkipString()         // mismatch_parameter
                       && cursor.Skip(2 * 8 + 2 * 8)  // strain_scale, strain_scale_std
                       && cursor.SkipString()         // strain_scale_source
                       && cursor.Skip(8 + 8)          // body_mass_kg, body_mass_std_kg
                       && cursor.SkipString()         // body_mass_source
                       && cursor.SkipString();        // vehicle_checksum
  return tail_ok ? DecodeError::kNone : cursor.error();
}

// Field layouts of the counted types, as in their .lcm files.
template <>
DecodeError CheckLengthFields<strain_n_t>(const uint8_t* data, size_t size) {
  return WalkLayout(data, size, {Bytes(kUtimeSeq), Count(), kDoubles});
}
template <>
DecodeError CheckLengthFields<motor_n_t>(const uint8_t* data, size_t size) {
  return WalkLayout(data, size, {Bytes(kUtimeSeq), Count(), kDoubles, kDoubles});
}
template <>
DecodeError CheckLengthFields<loadcell_n_t>(const uint8_t* data, size_t size) {
  return WalkLayout(data, size, {Bytes(kUtimeSeq), Count(), kDoubles});
}
template <>
DecodeError CheckLengthFields<truth_n_t>(const uint8_t* data, size_t size) {
  // utime, x, z, phi; n_arms; deflection; x_dot, z_dot, phi_dot; four arrays.
  return WalkLayout(data, size,
                    {Bytes(8 + 3 * 8), Count(), kDoubles, Bytes(3 * 8), kDoubles, kDoubles, kDoubles, kDoubles});
}
template <>
DecodeError CheckLengthFields<force_estimate_n_t>(const uint8_t* data, size_t size) {
  // force, std, thrust scale; status, rotor_fault_bits.
  return WalkLayout(data, size, {Bytes(kUtimeSeq), Count(), kDoubles, kDoubles, kDoubles, Bytes(4 + 4)});
}
template <>
DecodeError CheckLengthFields<motor_command_n_t>(const uint8_t* data, size_t size) {
  return WalkLayout(data, size, {Bytes(kUtimeSeq), Count(), kDoubles, Bytes(4 + 4)});  // mode, status
}
template <>
DecodeError CheckLengthFields<vehicle_description_t>(const uint8_t* data, size_t size) {
  // publisher, name, checksum; 8 body doubles; n_arms; angle, length, thrust
  // angle; spin; stiffness .. motor time constant; has_gauge; gauge scale, offset.
  return WalkLayout(data, size,
                    {Bytes(kUtimeSeq), String(), String(), String(), Bytes(8 * 8), Count(), kDoubles, kDoubles,
                     kDoubles, kInt8s, kDoubles, kDoubles, kDoubles, kDoubles, kDoubles, kInt8s, kDoubles, kDoubles});
}
template <>
DecodeError CheckLengthFields<estimator_learned_n_t>(const uint8_t* data, size_t size) {
  // vehicle_checksum; n_arms; strain scale, its std, source; tip mass, its
  // std, source; strain noise, source; body mass, its std, source.
  return WalkLayout(data, size,
                    {Bytes(kUtimeSeq), String(), Count(), kDoubles, kDoubles, String(), kDoubles, kDoubles, String(),
                     kDoubles, String(), Bytes(8 + 8), String()});
}
template <>
DecodeError CheckLengthFields<controller_rotors_n_t>(const uint8_t* data, size_t size) {
  // vehicle_checksum; n_rotors; efficiency, feasibility bound; weak_rotor
  // (int8_t), weak_efficiency.
  return WalkLayout(data, size, {Bytes(kUtimeSeq), String(), Count(), kDoubles, kDoubles, Bytes(1 + 8)});
}
// The sealed twins walk the nested message's layout, as its own walker above.
template <>
DecodeError CheckLengthFields<motor_command_n_auth_t>(const uint8_t* data, size_t size) {
  return WalkLayout(data, size, {kSealHeader, Bytes(kUtimeSeq), Count(), kDoubles, Bytes(4 + 4), kSealTag});
}
template <>
DecodeError CheckLengthFields<force_estimate_n_auth_t>(const uint8_t* data, size_t size) {
  return WalkLayout(data, size,
                    {kSealHeader, Bytes(kUtimeSeq), Count(), kDoubles, kDoubles, kDoubles, Bytes(4 + 4), kSealTag});
}

}  // namespace internal
}  // namespace birotor
