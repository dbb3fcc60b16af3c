// Tests of transport/counted_messages.h: the counted (_n_t) types round-trip
// for N = 2, 3 and 6; a count outside [2, 6], another vehicle's count or an
// inconsistent message is refused and counted; the birotor messages map to
// N = 2 and back bytewise; the vehicle description survives the wire with
// its checksum. Truncated and oversized packets of every counted type are
// in lcm_codec_test.cc (the type-parameterised codec suite).
#include "transport/counted_messages.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "model/vehicle_description_checksum.h"
#include "tests/transport/counted_test_messages.h"
#include "tests/transport/test_messages.h"
#include "transport/lcm_codec.h"

namespace birotor {
namespace {

using transport_test::Encode;
using transport_test::MakeCountedTestMessage;
using transport_test::MakeTestMessage;

// A receiver's description with n arms (only the count matters here).
VehicleDescription WithArms(int n) {
  VehicleDescription description;
  description.arm_count = n;
  return description;
}

// The count field of each counted type (n_arms or n_rotors).
int8_t& CountOf(strain_n_t& m) { return m.n_arms; }
int8_t& CountOf(motor_n_t& m) { return m.n_rotors; }
int8_t& CountOf(loadcell_n_t& m) { return m.n_rotors; }
int8_t& CountOf(truth_n_t& m) { return m.n_arms; }
int8_t& CountOf(force_estimate_n_t& m) { return m.n_rotors; }
int8_t& CountOf(motor_command_n_t& m) { return m.n_rotors; }
template <class Msg>
int CountOf(const Msg& m) {
  Msg copy = m;
  return CountOf(copy);
}

// Where the count sits in the encoded message: after the fingerprint,
// utime and seq (truth_n_t: utime, x, z, phi).
template <class Msg>
size_t CountOffset() {
  return 8 + 8 + 4;
}
template <>
size_t CountOffset<truth_n_t>() {
  return 8 + 8 + 3 * 8;
}

template <class Msg>
class CountedMessageTest : public ::testing::Test {};

using CountedMessages =
    ::testing::Types<strain_n_t, motor_n_t, loadcell_n_t, truth_n_t, force_estimate_n_t, motor_command_n_t>;
TYPED_TEST_SUITE(CountedMessageTest, CountedMessages);

TYPED_TEST(CountedMessageTest, RoundTripsForTwoThreeAndSixArms) {
  for (int n : {2, 3, kMaxArms}) {
    const TypeParam original = MakeCountedTestMessage<TypeParam>(n);
    const std::vector<uint8_t> bytes = Encode(original);
    TypeParam decoded{};
    ASSERT_EQ(DecodeMessage(bytes.data(), bytes.size(), &decoded), DecodeError::kNone) << "n " << n;
    EXPECT_EQ(Encode(decoded), bytes) << "n " << n;  // every field, NaN included
    EXPECT_EQ(CheckCount(decoded, WithArms(n)), CountCheck::kMatches) << "n " << n;
  }
}

TYPED_TEST(CountedMessageTest, ACountOutsideTwoToSixIsRefusedAndCounted) {
  CountRefusals refusals;
  for (int n : {0, 1, 7, -1, -128}) {
    // Arrays as long as the count where it can be, so only the count is wrong.
    TypeParam message = MakeCountedTestMessage<TypeParam>(n > 0 ? n : 0);
    CountOf(message) = static_cast<int8_t>(n);
    EXPECT_EQ(CheckCount(message, WithArms(3)), CountCheck::kOutOfRange) << "n " << n;
    EXPECT_FALSE(CountMatches(message, WithArms(3), &refusals)) << "n " << n;
  }
  EXPECT_EQ(refusals.out_of_range, 5);
  EXPECT_EQ(refusals.Total(), 5);
}

TYPED_TEST(CountedMessageTest, AnotherVehiclesCountIsRefusedAndCounted) {
  CountRefusals refusals;
  const TypeParam trirotor = MakeCountedTestMessage<TypeParam>(3);
  EXPECT_TRUE(CountMatches(trirotor, WithArms(3), &refusals));
  EXPECT_EQ(refusals.Total(), 0);  // a match counts nothing
  EXPECT_FALSE(CountMatches(trirotor, WithArms(2), &refusals));
  EXPECT_FALSE(CountMatches(trirotor, WithArms(kMaxArms), &refusals));
  EXPECT_FALSE(CountMatches(trirotor, WithArms(4), nullptr));  // counting is the caller's choice
  EXPECT_EQ(refusals.mismatch, 2);
  EXPECT_EQ(refusals.out_of_range, 0);
  EXPECT_EQ(refusals.Total(), 2);
}

TYPED_TEST(CountedMessageTest, AnArrayShorterThanTheCountIsInconsistent) {
  TypeParam message = MakeCountedTestMessage<TypeParam>(3);
  CountOf(message) = 4;  // arrays still hold 3
  CountRefusals refusals;
  EXPECT_EQ(CheckCount(message, WithArms(4)), CountCheck::kInconsistent);
  EXPECT_FALSE(CountMatches(message, WithArms(4), &refusals));
  EXPECT_EQ(refusals.inconsistent, 1);
}

TYPED_TEST(CountedMessageTest, ACountClaimingMoreThanThePacketIsTruncatedLessIsMalformed) {
  const std::vector<uint8_t> valid = Encode(MakeCountedTestMessage<TypeParam>(3));
  const size_t count_offset = CountOffset<TypeParam>();
  ASSERT_EQ(valid[count_offset], 3);
  std::vector<uint8_t> bytes = valid;
  for (int n : {4, kMaxArms, 7, 127}) {
    bytes[count_offset] = static_cast<uint8_t>(n);
    TypeParam decoded{};
    EXPECT_EQ(DecodeMessage(bytes.data(), bytes.size(), &decoded), DecodeError::kTruncated) << "n " << n;
  }
  for (int n : {0, 2}) {
    bytes[count_offset] = static_cast<uint8_t>(n);
    TypeParam decoded{};
    EXPECT_EQ(DecodeMessage(bytes.data(), bytes.size(), &decoded), DecodeError::kMalformed) << "n " << n;
  }
  for (int n : {-1, -128}) {  // a negative count: no vector of 2^64 elements
    bytes[count_offset] = static_cast<uint8_t>(static_cast<int8_t>(n));
    TypeParam decoded{};
    EXPECT_EQ(DecodeMessage(bytes.data(), bytes.size(), &decoded), DecodeError::kMalformed) << "n " << n;
  }
}

// The birotor message and its counted twin.
template <class Birotor, class Counted>
struct Twins {
  using BirotorType = Birotor;
  using CountedType = Counted;
};

template <class T>
class BirotorTwinTest : public ::testing::Test {};

using BirotorTwins =
    ::testing::Types<Twins<strain_t, strain_n_t>, Twins<motor_t, motor_n_t>, Twins<loadcell_t, loadcell_n_t>,
                     Twins<truth_t, truth_n_t>, Twins<force_estimate_t, force_estimate_n_t>,
                     Twins<motor_command_t, motor_command_n_t>>;
TYPED_TEST_SUITE(BirotorTwinTest, BirotorTwins);

TYPED_TEST(BirotorTwinTest, TheBirotorMessageIsTheCountedOneWithTwoArmsAndBack) {
  using Birotor = typename TypeParam::BirotorType;
  const Birotor original = MakeTestMessage<Birotor>();
  const auto counted = ToCountedMessage(original);
  EXPECT_EQ(CountOf(counted), 2);
  EXPECT_EQ(CheckCount(counted, WithArms(2)), CountCheck::kMatches);
  // Through the wire, as an old log read through the new path would be.
  const std::vector<uint8_t> bytes = Encode(counted);
  typename TypeParam::CountedType decoded{};
  ASSERT_EQ(DecodeMessage(bytes.data(), bytes.size(), &decoded), DecodeError::kNone);
  Birotor back{};
  ASSERT_TRUE(ToBirotorMessage(decoded, &back));
  EXPECT_EQ(Encode(back), Encode(original));  // every field, NaN included
}

TYPED_TEST(BirotorTwinTest, OnlyATwoArmMessageBecomesABirotorOne) {
  using Birotor = typename TypeParam::BirotorType;
  const Birotor untouched = MakeTestMessage<Birotor>();
  for (int n : {3, kMaxArms}) {
    Birotor out = untouched;
    EXPECT_FALSE(ToBirotorMessage(MakeCountedTestMessage<typename TypeParam::CountedType>(n), &out)) << "n " << n;
    EXPECT_EQ(Encode(out), Encode(untouched));
  }
  auto inconsistent = MakeCountedTestMessage<typename TypeParam::CountedType>(3);
  CountOf(inconsistent) = 2;  // arrays of 3 under a count of 2
  Birotor out = untouched;
  EXPECT_FALSE(ToBirotorMessage(inconsistent, &out));
}

TEST(BirotorTwinTest, StrainFieldsMapByName) {
  const strain_n_t counted = ToCountedMessage(MakeTestMessage<strain_t>());
  EXPECT_EQ(counted.utime, 1234567);
  EXPECT_EQ(counted.seq, 42);
  EXPECT_EQ(counted.n_arms, 2);
  EXPECT_EQ(counted.deflection_rad, (std::vector<double>{-0.0123, 0.0125}));
}

TEST(BirotorTwinTest, TheTwoRotorBitsBecomeRotorFaultBitsZeroAndOne) {
  force_estimate_t birotor = MakeTestMessage<force_estimate_t>();
  birotor.status = force_estimate_t::STATUS_CONVERGING | force_estimate_t::STATUS_ROTOR2_FAULT |
                   force_estimate_t::STATUS_MODEL_MISMATCH;
  force_estimate_n_t counted = ToCountedMessage(birotor);
  EXPECT_EQ(counted.status, force_estimate_n_t::STATUS_CONVERGING | force_estimate_n_t::STATUS_MODEL_MISMATCH);
  EXPECT_EQ(counted.rotor_fault_bits, force_estimate_n_t::ROTOR_FAULT_ROTOR2);

  birotor.status = force_estimate_t::STATUS_ROTOR1_FAULT | force_estimate_t::STATUS_ROTOR2_FAULT;
  counted = ToCountedMessage(birotor);
  EXPECT_EQ(counted.status, 0);
  EXPECT_EQ(counted.rotor_fault_bits, 0b11);
}

TEST(BirotorTwinTest, VehicleWideBitsKeepTheirValues) {
  // force_estimate_n_t's vehicle-wide constants are force_estimate_t's.
  EXPECT_EQ(force_estimate_n_t::STATUS_VALID, force_estimate_t::STATUS_VALID);
  EXPECT_EQ(force_estimate_n_t::STATUS_CONVERGING, force_estimate_t::STATUS_CONVERGING);
  EXPECT_EQ(force_estimate_n_t::STATUS_MEASUREMENT_REJECTED, force_estimate_t::STATUS_MEASUREMENT_REJECTED);
  EXPECT_EQ(force_estimate_n_t::STATUS_INPUT_STALE, force_estimate_t::STATUS_INPUT_STALE);
  EXPECT_EQ(force_estimate_n_t::STATUS_FILTER_RESET, force_estimate_t::STATUS_FILTER_RESET);
  EXPECT_EQ(force_estimate_n_t::STATUS_NO_MOTOR_INPUT, force_estimate_t::STATUS_NO_MOTOR_INPUT);
  EXPECT_EQ(force_estimate_n_t::STATUS_THRUST_DEFICIT, force_estimate_t::STATUS_THRUST_DEFICIT);
  EXPECT_EQ(force_estimate_n_t::STATUS_INPUT_CONFLICT, force_estimate_t::STATUS_INPUT_CONFLICT);
  EXPECT_EQ(force_estimate_n_t::STATUS_MODEL_MISMATCH, force_estimate_t::STATUS_MODEL_MISMATCH);
  EXPECT_EQ(motor_command_n_t::STATUS_MPC_FALLBACK, motor_command_t::STATUS_MPC_FALLBACK);
  EXPECT_EQ(motor_command_n_t::MODE_MPC, motor_command_t::MODE_MPC);
}

TEST(CountedMessageTest, ARotorFaultBitBeyondTheCountIsInconsistent) {
  force_estimate_n_t message = MakeCountedTestMessage<force_estimate_n_t>(3);
  message.rotor_fault_bits = force_estimate_n_t::ROTOR_FAULT_ROTOR3;  // rotor 3 of 3
  EXPECT_EQ(CheckCount(message, WithArms(3)), CountCheck::kMatches);
  message.rotor_fault_bits = force_estimate_n_t::ROTOR_FAULT_ROTOR4;  // rotor 4 of 3
  EXPECT_EQ(CheckCount(message, WithArms(3)), CountCheck::kInconsistent);
  message.rotor_fault_bits = -1;
  EXPECT_EQ(CheckCount(message, WithArms(3)), CountCheck::kInconsistent);
}

TEST(CountedMessageTest, CheckNames) {
  EXPECT_STREQ(CountCheckName(CountCheck::kMatches), "matches");
  EXPECT_STREQ(CountCheckName(CountCheck::kOutOfRange), "out_of_range");
  EXPECT_STREQ(CountCheckName(CountCheck::kMismatch), "mismatch");
  EXPECT_STREQ(CountCheckName(CountCheck::kInconsistent), "inconsistent");
}

// A trirotor drawn by hand (config/vehicles/trirotor.yaml is read in
// tests/params): arms at 90, 210 and 330 degrees, one without a gauge.
VehicleDescription HandMadeTrirotor() {
  VehicleDescription d;
  d.name = "trirotor";
  d.arm_count = 3;
  for (int i = 0; i < 3; ++i) d.arms[static_cast<size_t>(i)].angle_rad = M_PI / 2 + i * 2 * M_PI / 3;
  d.arms[1].spin = -1;
  d.arms[2].has_gauge = false;
  d.arms[2].thrust_angle_rad = 0.1;
  d.body_mass_kg = 3.5;
  return d;
}

TEST(VehicleDescriptionMessageTest, TheDescriptionSurvivesTheWireWithItsChecksum) {
  const VehicleDescription original = HandMadeTrirotor();
  vehicle_description_t message = ToMessage(original, "birotor-test");
  EXPECT_EQ(message.publisher, "birotor-test");
  EXPECT_EQ(message.name, "trirotor");
  EXPECT_EQ(message.n_arms, 3);
  EXPECT_EQ(message.checksum, DescriptionChecksum(original));
  EXPECT_EQ(message.spin, (std::vector<int8_t>{1, -1, 1}));
  EXPECT_EQ(message.has_gauge, (std::vector<int8_t>{1, 1, 0}));
  const std::vector<uint8_t> bytes = Encode(message);
  vehicle_description_t decoded{};
  ASSERT_EQ(DecodeMessage(bytes.data(), bytes.size(), &decoded), DecodeError::kNone);
  VehicleDescription read;
  std::string why;
  ASSERT_TRUE(FromMessage(decoded, &read, &why)) << why;
  EXPECT_EQ(FirstDifference(read, original), "");
  EXPECT_EQ(DescriptionChecksum(read), DescriptionChecksum(original));  // bit for bit
}

TEST(VehicleDescriptionMessageTest, AChecksumThatIsNotTheFieldsOnesIsRefused) {
  vehicle_description_t message = ToMessage(HandMadeTrirotor(), "birotor-test");
  message.tip_mass_kg[1] += 1e-9;  // a field changed after the checksum was taken
  VehicleDescription read = WithArms(2);
  std::string why;
  EXPECT_FALSE(FromMessage(message, &read, &why));
  EXPECT_NE(why.find("checksum"), std::string::npos) << why;
  EXPECT_EQ(read.arm_count, 2);  // untouched
}

TEST(VehicleDescriptionMessageTest, ABadCountIsRefused) {
  for (int n : {0, 7, -1}) {
    vehicle_description_t message = ToMessage(HandMadeTrirotor(), "birotor-test");
    message.n_arms = static_cast<int8_t>(n);
    VehicleDescription read;
    std::string why;
    EXPECT_FALSE(FromMessage(message, &read, &why)) << "n " << n;
    EXPECT_NE(why.find("out_of_range"), std::string::npos) << why;
  }
  vehicle_description_t short_array = ToMessage(HandMadeTrirotor(), "birotor-test");
  short_array.gauge_offset_rad.pop_back();
  VehicleDescription read;
  std::string why;
  EXPECT_FALSE(FromMessage(short_array, &read, &why));
  EXPECT_NE(why.find("inconsistent"), std::string::npos) << why;
}

}  // namespace
}  // namespace birotor

namespace birotor {
namespace {

// The N-arm EKF's estimate on the wire: n_rotors entries, status and
// rotor_fault_bits copied as composed.
TEST(MultiArmForceMessageTest, ThreeRotorsFieldForField) {
  MultiArmForceEstimate e;
  e.utime = 123456;
  e.seq = 7;
  e.n_rotors = 3;
  e.force_n = {27.5, 14.3, 14.2, 99, 99, 99};
  e.force_std_n = {0.1, 0.2, 0.3, 9, 9, 9};
  e.thrust_scale = {1.0, 0.75, 1.01, 9, 9, 9};
  e.status = force_estimate_n_t::STATUS_VALID | force_estimate_n_t::STATUS_MEASUREMENT_REJECTED;
  e.rotor_fault_bits = force_estimate_n_t::ROTOR_FAULT_ROTOR2;
  const force_estimate_n_t m = ToMessage(e);
  EXPECT_EQ(m.utime, 123456);
  EXPECT_EQ(m.seq, 7);
  ASSERT_EQ(m.n_rotors, 3);
  EXPECT_EQ(m.force_n, (std::vector<double>{27.5, 14.3, 14.2}));
  EXPECT_EQ(m.force_std_n, (std::vector<double>{0.1, 0.2, 0.3}));
  EXPECT_EQ(m.thrust_scale, (std::vector<double>{1.0, 0.75, 1.01}));
  EXPECT_EQ(m.status, e.status);
  EXPECT_EQ(m.rotor_fault_bits, force_estimate_n_t::ROTOR_FAULT_ROTOR2);
}

}  // namespace
}  // namespace birotor
