// Tests of transport/lcm_codec.h: round trips of every type, and rejection of
// garbage, foreign fingerprints, truncated packets, trailing bytes and
// corrupt length fields without a crash or an exception.
#include "transport/lcm_codec.h"

#include <gtest/gtest.h>

#include <climits>
#include <cstring>
#include <random>
#include <vector>

#include "tests/transport/counted_test_messages.h"
#include "tests/transport/sealed_and_status_test_messages.h"
#include "tests/transport/test_messages.h"

namespace birotor {
namespace {

using transport_test::Encode;
using transport_test::kTestArmCount;
using transport_test::MakeTestMessage;

template <class Msg>
class CodecTest : public ::testing::Test {};

// Every type of lcmtypes/.
using AllMessages =
    ::testing::Types<strain_t, motor_t, imu_t, pose_t, loadcell_t, truth_t, force_estimate_t, motor_command_t,
                     input_health_t, estimator_status_t, strain_n_t, motor_n_t, loadcell_n_t, truth_n_t,
                     force_estimate_n_t, motor_command_n_t, vehicle_description_t, estimator_learned_n_t,
                     controller_rotors_n_t, setpoint_t, controller_status_t, guard_status_t, motor_command_auth_t,
                     setpoint_auth_t, pose_auth_t, force_estimate_auth_t, motor_command_n_auth_t,
                     force_estimate_n_auth_t>;
TYPED_TEST_SUITE(CodecTest, AllMessages);

TYPED_TEST(CodecTest, RoundTripReproducesTheBytes) {
  const TypeParam original = MakeTestMessage<TypeParam>();
  const std::vector<uint8_t> bytes = Encode(original);
  ASSERT_EQ(static_cast<int>(bytes.size()), original.getEncodedSize());

  TypeParam decoded{};
  ASSERT_EQ(DecodeMessage(bytes.data(), bytes.size(), &decoded), DecodeError::kNone);
  // Byte equality of the re-encoding compares every field, NaN included.
  EXPECT_EQ(Encode(decoded), bytes);
}

TYPED_TEST(CodecTest, EveryPrefixIsTruncated) {
  const std::vector<uint8_t> bytes = Encode(MakeTestMessage<TypeParam>());
  for (size_t size = 0; size < bytes.size(); ++size) {
    TypeParam decoded{};
    EXPECT_EQ(DecodeMessage(bytes.data(), size, &decoded), DecodeError::kTruncated)
        << "prefix of " << size << " of " << bytes.size() << " bytes";
  }
}

TYPED_TEST(CodecTest, TrailingBytesAreMalformed) {
  std::vector<uint8_t> bytes = Encode(MakeTestMessage<TypeParam>());
  bytes.push_back(0);
  TypeParam decoded{};
  EXPECT_EQ(DecodeMessage(bytes.data(), bytes.size(), &decoded), DecodeError::kMalformed);
}

TYPED_TEST(CodecTest, RandomBytesAreRejected) {
  std::mt19937 random(1);
  std::uniform_int_distribution<int> byte(0, 255);
  for (size_t size = 0; size < 400; ++size) {
    std::vector<uint8_t> bytes(size);
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(byte(random));
    TypeParam decoded{};
    EXPECT_NE(DecodeMessage(bytes.data(), bytes.size(), &decoded), DecodeError::kNone);
  }
}

TYPED_TEST(CodecTest, RandomPayloadBehindAValidFingerprintNeverCrashes) {
  const std::vector<uint8_t> valid = Encode(MakeTestMessage<TypeParam>());
  std::mt19937 random(2);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<uint8_t> bytes(valid.begin(), valid.begin() + 8);
    bytes.resize(8 + static_cast<size_t>(trial % 300));
    for (size_t i = 8; i < bytes.size(); ++i) bytes[i] = static_cast<uint8_t>(byte(random));
    TypeParam decoded{};
    if (DecodeMessage(bytes.data(), bytes.size(), &decoded) == DecodeError::kNone) {
      EXPECT_EQ(Encode(decoded), bytes);  // accepted only if it is exactly one message
    }
  }
}

TEST(CodecTest, OtherTypeHasBadFingerprint) {
  const std::vector<uint8_t> motor_bytes = Encode(MakeTestMessage<motor_t>());
  strain_t strain{};
  EXPECT_EQ(DecodeMessage(motor_bytes.data(), motor_bytes.size(), &strain), DecodeError::kBadFingerprint);

  const std::vector<uint8_t> strain_bytes = Encode(MakeTestMessage<strain_t>());
  loadcell_t loadcell{};  // same layout as strain_t, different type name
  EXPECT_EQ(DecodeMessage(strain_bytes.data(), strain_bytes.size(), &loadcell), DecodeError::kBadFingerprint);
}

TEST(CodecTest, NullDataIsTruncated) {
  strain_t strain{};
  EXPECT_EQ(DecodeMessage(nullptr, 0, &strain), DecodeError::kTruncated);
}

// Offsets into an encoded estimator_status_t, from lcmtypes/estimator_status_t.lcm.
constexpr size_t kMethodLengthOffset = 8 + 8 + 8 + 4;

void WriteInt32(std::vector<uint8_t>* bytes, size_t offset, int32_t value) {
  const auto raw = static_cast<uint32_t>(value);
  for (int i = 0; i < 4; ++i) (*bytes)[offset + i] = static_cast<uint8_t>(raw >> (24 - 8 * i));
}

template <class Msg>
DecodeError Decode(const std::vector<uint8_t>& bytes) {
  Msg decoded{};
  return DecodeMessage(bytes.data(), bytes.size(), &decoded);
}

DecodeError DecodeStatus(const std::vector<uint8_t>& bytes) { return Decode<estimator_status_t>(bytes); }

// Every field overwritten with the values a corrupt length or count takes
// (negative, zero, huge, past the end). Whatever CheckLengthFields lets
// through, the generated decoder takes without throwing: a type with a
// string or a variable-length array and no specialisation fails here. And
// DecodeMessage accepts only exactly one message.
TYPED_TEST(CodecTest, NoCorruptLengthGetsPastTheCheckToTheGeneratedDecoder) {
  const std::vector<uint8_t> valid = Encode(MakeTestMessage<TypeParam>());
  const auto check = [](const std::vector<uint8_t>& bytes, size_t offset) {
    if (internal::CheckLengthFields<TypeParam>(bytes.data(), bytes.size()) == DecodeError::kNone) {
      TypeParam unchecked{};
      EXPECT_NO_THROW(unchecked.decode(bytes.data(), 0, static_cast<int>(bytes.size()))) << "offset " << offset;
    }
    TypeParam decoded{};
    if (DecodeMessage(bytes.data(), bytes.size(), &decoded) != DecodeError::kNone) return;
    const std::vector<uint8_t> again = Encode(decoded);
    if (!again.empty()) EXPECT_EQ(again, bytes) << "offset " << offset;  // empty: a NUL inside a string
  };
  const auto past_the_end = static_cast<int32_t>(valid.size());
  for (size_t offset = 8; offset < valid.size(); ++offset) {
    for (int8_t count : {int8_t{-128}, int8_t{-1}, int8_t{0}, int8_t{127}}) {
      std::vector<uint8_t> bytes = valid;
      bytes[offset] = static_cast<uint8_t>(count);
      check(bytes, offset);
    }
    if (offset + 4 > valid.size()) continue;
    for (int32_t length : {INT_MIN, -1, 0, past_the_end, INT_MAX}) {
      std::vector<uint8_t> bytes = valid;
      WriteInt32(&bytes, offset, length);
      check(bytes, offset);
    }
  }
}

TEST(CodecTest, CorruptStringLengthIsRejected) {
  const std::vector<uint8_t> valid = Encode(MakeTestMessage<estimator_status_t>());
  for (int32_t length : {0, -1, -100, INT_MIN, INT_MAX, 100000}) {
    std::vector<uint8_t> bytes = valid;
    WriteInt32(&bytes, kMethodLengthOffset, length);
    EXPECT_NE(DecodeStatus(bytes), DecodeError::kNone) << "length " << length;
  }
  std::vector<uint8_t> no_terminator = valid;
  no_terminator[kMethodLengthOffset + 4 + 3] = 'x';  // "ekf\0" -> "ekfx"
  EXPECT_EQ(DecodeStatus(no_terminator), DecodeError::kMalformed);
}

// libFuzzer (decode_fuzzer, 10-minute run): the strings added after
// thrust_scale (gauge_offset_source, last_tare_refusal) were not walked, so a
// length of INT_MIN reached the generated decoder (signed overflow, then a
// 2 GB copy). Offsets from the end: four int64 udp counters close the message.
TEST(CodecTest, CorruptLengthOfTheLaterStringsIsRejected) {
  const estimator_status_t message = MakeTestMessage<estimator_status_t>();
  const std::vector<uint8_t> valid = Encode(message);
  // The message ends with the udp counters, the accelerometer's
  // input_health_t, foreign_force (8 bytes), model_consistency_statistic
  // (8 bytes), mismatch_parameter, then the learned parameters:
  // strain_scale[2], strain_scale_std[2], strain_scale_source, body_mass_kg,
  // body_mass_std_kg, body_mass_source, and vehicle_checksum.
  const size_t checksum_length_offset = valid.size() - (message.vehicle_checksum.size() + 1) - 4;
  const size_t mass_source_length_offset = checksum_length_offset - (message.body_mass_source.size() + 1) - 4;
  const size_t scale_source_length_offset =
      mass_source_length_offset - 2 * 8 - (message.strain_scale_source.size() + 1) - 4;
  const size_t parameter_length_offset =
      scale_source_length_offset - 4 * 8 - (message.mismatch_parameter.size() + 1) - 4;
  const size_t accelerometer_offset = parameter_length_offset - 8 - 8 - (message.accelerometer.getEncodedSize() - 8);
  const size_t refusal_length_offset = accelerometer_offset - 4 * 8 - (message.last_tare_refusal.size() + 1) - 4;
  const size_t source_length_offset = refusal_length_offset - 4 * 8 - (message.gauge_offset_source.size() + 1) - 4;
  for (const size_t offset :
       {checksum_length_offset, mass_source_length_offset, scale_source_length_offset, parameter_length_offset,
        accelerometer_offset, refusal_length_offset, source_length_offset}) {
    for (int32_t length : {0, -1, INT_MIN, INT_MAX}) {
      std::vector<uint8_t> bytes = valid;
      WriteInt32(&bytes, offset, length);
      EXPECT_NE(DecodeStatus(bytes), DecodeError::kNone) << "offset " << offset << " length " << length;
    }
  }
}

TEST(CodecTest, CorruptStringLengthInAStandaloneInputHealthIsRejected) {
  const std::vector<uint8_t> valid = Encode(MakeTestMessage<input_health_t>());
  for (int32_t length : {0, -1, INT_MIN, INT_MAX}) {
    std::vector<uint8_t> bytes = valid;
    WriteInt32(&bytes, 8, length);  // channel length follows the fingerprint
    input_health_t health{};
    EXPECT_NE(DecodeMessage(bytes.data(), bytes.size(), &health), DecodeError::kNone) << "length " << length;
  }
}

TEST(CodecTest, CorruptArrayCountIsRejected) {
  const estimator_status_t message = MakeTestMessage<estimator_status_t>();
  const std::vector<uint8_t> valid = Encode(message);
  const size_t num_inputs_offset = kMethodLengthOffset + 4 + message.method.size() + 1 + 4;
  for (int32_t count : {-1, INT_MIN, INT_MAX, 5, 1000000}) {
    std::vector<uint8_t> bytes = valid;
    WriteInt32(&bytes, num_inputs_offset, count);
    EXPECT_NE(DecodeStatus(bytes), DecodeError::kNone) << "count " << count;
  }
  std::vector<uint8_t> negative = valid;
  WriteInt32(&negative, num_inputs_offset, -1);
  EXPECT_EQ(DecodeStatus(negative), DecodeError::kMalformed);
}

// estimator_learned_n_t (lcmtypes/estimator_learned_n_t.lcm): its five
// strings and its count are walked before the generated decoder runs.
TEST(CodecTest, CorruptLengthsOfTheLearnedValuesAreRejected) {
  const estimator_learned_n_t message = MakeTestMessage<estimator_learned_n_t>();
  const std::vector<uint8_t> valid = Encode(message);
  const auto decode = [](const std::vector<uint8_t>& bytes) {
    estimator_learned_n_t decoded{};
    return DecodeMessage(bytes.data(), bytes.size(), &decoded);
  };
  const size_t arrays = 8 * static_cast<size_t>(message.n_arms);
  const size_t checksum_length_offset = 8 + 8 + 4;
  const size_t count_offset = checksum_length_offset + 4 + message.vehicle_checksum.size() + 1;
  const size_t scale_source_offset = count_offset + 1 + 2 * arrays;
  const size_t tip_source_offset = scale_source_offset + 4 + message.strain_scale_source.size() + 1 + 2 * arrays;
  const size_t noise_source_offset = tip_source_offset + 4 + message.tip_mass_source.size() + 1 + arrays;
  const size_t mass_source_offset = noise_source_offset + 4 + message.strain_noise_source.size() + 1 + 2 * 8;
  ASSERT_EQ(mass_source_offset + 4 + message.body_mass_source.size() + 1, valid.size());
  for (const size_t offset :
       {checksum_length_offset, scale_source_offset, tip_source_offset, noise_source_offset, mass_source_offset}) {
    for (int32_t length : {0, -1, INT_MIN, INT_MAX}) {
      std::vector<uint8_t> bytes = valid;
      WriteInt32(&bytes, offset, length);
      EXPECT_NE(decode(bytes), DecodeError::kNone) << "offset " << offset << " length " << length;
    }
  }
  std::vector<uint8_t> negative = valid;
  negative[count_offset] = 0xff;  // n_arms -1
  EXPECT_EQ(decode(negative), DecodeError::kMalformed);
  std::vector<uint8_t> longer = valid;
  longer[count_offset] = 100;  // arrays past the end
  EXPECT_EQ(decode(longer), DecodeError::kTruncated);
}

// A corrupt arm count of a test message (kTestArmCount arms) and what it
// decodes to: negative, more arms than the bytes hold, or fewer (2: bytes left
// after the message).
constexpr std::pair<int8_t, DecodeError> kCorruptArmCounts[] = {{-1, DecodeError::kMalformed},
                                                                {-128, DecodeError::kMalformed},
                                                                {4, DecodeError::kTruncated},
                                                                {127, DecodeError::kTruncated},
                                                                {2, DecodeError::kMalformed}};

// controller_rotors_n_t (lcmtypes/controller_rotors_n_t.lcm): its string and
// its count are walked before the generated decoder runs. The walker itself
// rejects them (the generic CheckLengthFields lets everything through, and
// the generated decoder would then overflow on a string length of INT_MIN).
TEST(CodecTest, CorruptLengthsOfTheControllerRotorsAreRejected) {
  const controller_rotors_n_t message = MakeTestMessage<controller_rotors_n_t>();
  const std::vector<uint8_t> valid = Encode(message);
  const size_t checksum_length_offset = 8 + 8 + 4;
  const size_t count_offset = checksum_length_offset + 4 + message.vehicle_checksum.size() + 1;
  const size_t arrays = 8 * static_cast<size_t>(message.n_rotors);
  ASSERT_EQ(count_offset + 1 + 2 * arrays + 1 + 8, valid.size());  // weak_rotor, weak_efficiency close it
  const int32_t checksum_bytes = static_cast<int32_t>(message.vehicle_checksum.size()) + 1;
  // Negative or zero, past the end, or ending on a byte that is not the NUL.
  const std::pair<int32_t, DecodeError> lengths[] = {{0, DecodeError::kMalformed},
                                                     {-1, DecodeError::kMalformed},
                                                     {INT_MIN, DecodeError::kMalformed},
                                                     {INT_MAX, DecodeError::kTruncated},
                                                     {1000, DecodeError::kTruncated},
                                                     {checksum_bytes - 1, DecodeError::kMalformed},
                                                     {checksum_bytes + 1, DecodeError::kMalformed}};
  for (const auto& [length, expected] : lengths) {
    std::vector<uint8_t> bytes = valid;
    WriteInt32(&bytes, checksum_length_offset, length);
    EXPECT_EQ(internal::CheckLengthFields<controller_rotors_n_t>(bytes.data(), bytes.size()), expected)
        << "length " << length;
    EXPECT_EQ(Decode<controller_rotors_n_t>(bytes), expected) << "length " << length;
  }
  for (const auto& [count, expected] : kCorruptArmCounts) {
    std::vector<uint8_t> bytes = valid;
    bytes[count_offset] = static_cast<uint8_t>(count);
    EXPECT_EQ(Decode<controller_rotors_n_t>(bytes), expected) << "count " << int{count};
  }
}

// The sealed N-arm twins (motor_command_n_auth_t, force_estimate_n_auth_t)
// nest a counted message: its count is walked inside the envelope.
template <class Sealed>
void ExpectCorruptCountInTheEnvelopeRejected() {
  const std::vector<uint8_t> valid = Encode(MakeTestMessage<Sealed>());
  const size_t count_offset = 8 + 8 + 8 + 8 + 4;  // fingerprint, publisher, counter, utime, seq
  ASSERT_EQ(valid[count_offset], kTestArmCount);
  for (const auto& [count, expected] : kCorruptArmCounts) {
    std::vector<uint8_t> bytes = valid;
    bytes[count_offset] = static_cast<uint8_t>(count);
    if (count < 0 || count > kTestArmCount) {
      EXPECT_EQ(internal::CheckLengthFields<Sealed>(bytes.data(), bytes.size()), expected) << "count " << int{count};
    }
    EXPECT_EQ(Decode<Sealed>(bytes), expected) << "count " << int{count};
  }
}

TEST(CodecTest, CorruptCountInsideASealedNArmMessageIsRejected) {
  ExpectCorruptCountInTheEnvelopeRejected<motor_command_n_auth_t>();
  ExpectCorruptCountInTheEnvelopeRejected<force_estimate_n_auth_t>();
}

TEST(CodecTest, EmptyArrayDecodes) {
  estimator_status_t message = MakeTestMessage<estimator_status_t>();
  message.inputs.clear();
  message.num_inputs = 0;
  message.method = "";
  const std::vector<uint8_t> bytes = Encode(message);
  estimator_status_t decoded{};
  ASSERT_EQ(DecodeMessage(bytes.data(), bytes.size(), &decoded), DecodeError::kNone);
  EXPECT_EQ(decoded.num_inputs, 0);
  EXPECT_EQ(decoded.method, "");
  EXPECT_EQ(decoded.last_reset_reason, "start");
}

TEST(CodecTest, EncodeReusesTheBuffer) {
  std::vector<uint8_t> buffer;
  EncodeMessage(MakeTestMessage<estimator_status_t>(), &buffer);
  const uint8_t* storage = buffer.data();
  const size_t capacity = buffer.capacity();

  EncodeMessage(MakeTestMessage<strain_t>(), &buffer);
  EXPECT_EQ(static_cast<int>(buffer.size()), MakeTestMessage<strain_t>().getEncodedSize());
  EncodeMessage(MakeTestMessage<estimator_status_t>(), &buffer);
  EXPECT_EQ(buffer.data(), storage);
  EXPECT_EQ(buffer.capacity(), capacity);
}

TEST(CodecTest, ErrorNames) {
  EXPECT_STREQ(DecodeErrorName(DecodeError::kNone), "none");
  EXPECT_STREQ(DecodeErrorName(DecodeError::kTruncated), "truncated");
  EXPECT_STREQ(DecodeErrorName(DecodeError::kBadFingerprint), "bad_fingerprint");
  EXPECT_STREQ(DecodeErrorName(DecodeError::kMalformed), "malformed");
}

}  // namespace
}  // namespace birotor
