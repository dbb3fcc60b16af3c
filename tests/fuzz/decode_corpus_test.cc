// Tests of the decode fuzzer's table and seed corpus (fuzz/decode_targets.h,
// fuzz/corpus/decode_fuzzer/): every lcmtypes/*.lcm type is a target, the
// first nine keep their selectors, and every seed is a packet of the type its
// first byte selects, valid unless it is a reproducer of a fixed finding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "fuzz/decode_targets.h"

namespace birotor::fuzz {
namespace {

namespace fs = std::filesystem;

// Seeds that reproduce a fixed finding: their length fields are corrupt on purpose.
const std::set<std::string> kReproducers = {"status_gauge_source_length_int_min",
                                            "controller_rotors_checksum_length_int_min"};

struct Seed {
  std::string name;
  std::vector<uint8_t> bytes;  // selector byte, then the packet
};

std::vector<Seed> ReadCorpus() {
  std::vector<Seed> seeds;
  for (const auto& entry : fs::directory_iterator(fs::path(BIROTOR_SOURCE_DIR) / "fuzz/corpus/decode_fuzzer")) {
    std::ifstream in(entry.path(), std::ios::binary);
    seeds.push_back({entry.path().filename().string(),
                     std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>())});
  }
  return seeds;
}

uint64_t WireFingerprint(const uint8_t* packet) {
  uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value = (value << 8) | packet[i];
  return value;
}

std::vector<const DecodeTarget*> AllTargets() {
  std::vector<const DecodeTarget*> targets;
  for (const DecodeTarget& target : kBirotorTargets) targets.push_back(&target);
  for (const DecodeTarget& target : kLaterTargets) targets.push_back(&target);
  return targets;
}

TEST(DecodeCorpusTest, TheFirstNineKeepTheirSelectors) {
  const char* const first_nine[] = {
      "strain_t",           "motor_t",       "imu_t", "pose_t", "loadcell_t", "truth_t", "force_estimate_t",
      "estimator_status_t", "input_health_t"};
  for (int selector = 0; selector < 9; ++selector) {
    EXPECT_STREQ(TargetOf(static_cast<uint8_t>(selector)).type_name, first_nine[selector]);
  }
  EXPECT_STREQ(TargetOf(0xFA).type_name, "estimator_status_t");  // 250 % 9 = 7
  EXPECT_STREQ(TargetOf(0x7F).type_name, "motor_t");             // 127 % 9 = 1, just below the later range
  const auto after_the_later_range = static_cast<uint8_t>(kFirstLaterSelector + kNumLaterTargets);
  EXPECT_STREQ(TargetOf(after_the_later_range).type_name,
               kBirotorTargets[after_the_later_range % std::size(kBirotorTargets)].type_name);
  EXPECT_STREQ(TargetOf(kFirstLaterSelector).type_name, "strain_n_t");
}

TEST(DecodeCorpusTest, EveryLcmTypeIsATargetOnce) {
  std::set<std::string> lcm_types;
  for (const auto& entry : fs::directory_iterator(fs::path(BIROTOR_SOURCE_DIR) / "lcmtypes")) {
    if (entry.path().extension() == ".lcm") lcm_types.insert(entry.path().stem().string());
  }
  std::set<std::string> target_types;
  for (const DecodeTarget* target : AllTargets()) {
    EXPECT_TRUE(target_types.insert(target->type_name).second) << target->type_name << " twice";
  }
  EXPECT_EQ(target_types, lcm_types);
}

TEST(DecodeCorpusTest, EverySeedIsAPacketOfTheTypeItsSelectorPicks) {
  const std::vector<Seed> seeds = ReadCorpus();
  ASSERT_FALSE(seeds.empty());
  for (const Seed& seed : seeds) {
    ASSERT_GE(seed.bytes.size(), 1u + 8u) << seed.name;
    const DecodeTarget& target = TargetOf(seed.bytes[0]);
    const uint8_t* packet = seed.bytes.data() + 1;
    const size_t size = seed.bytes.size() - 1;
    EXPECT_EQ(WireFingerprint(packet), target.fingerprint()) << seed.name << " is not a " << target.type_name;
    const DecodeError verdict = target.decode(packet, size);
    if (kReproducers.count(seed.name) != 0) {
      EXPECT_EQ(verdict, DecodeError::kMalformed) << seed.name << ": " << DecodeErrorName(verdict);
    } else {
      EXPECT_EQ(verdict, DecodeError::kNone)
          << seed.name << " as " << target.type_name << ": " << DecodeErrorName(verdict);
    }
  }
}

TEST(DecodeCorpusTest, EveryTargetHasAValidSeed) {
  std::set<std::string> seeded;
  for (const Seed& seed : ReadCorpus()) {
    if (seed.bytes.size() < 1 + 8) continue;
    const DecodeTarget& target = TargetOf(seed.bytes[0]);
    if (target.decode(seed.bytes.data() + 1, seed.bytes.size() - 1) == DecodeError::kNone) {
      seeded.insert(target.type_name);
    }
  }
  for (const DecodeTarget* target : AllTargets()) {
    EXPECT_EQ(seeded.count(target->type_name), 1u) << "no valid seed of " << target->type_name;
  }
}

}  // namespace
}  // namespace birotor::fuzz
