// Tests of model/vehicle_description_checksum.h: the canonical text names
// every field at full precision, the checksum is FNV-1a 64 of it, and any
// one changed field changes it. The value for config/vehicles/birotor.yaml is
// asserted where that file is read (tests/params/vehicle_description_yaml_test.cc).
#include "model/vehicle_description_checksum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "numerics/fnv1a.h"

namespace birotor {
namespace {

TEST(VehicleDescriptionChecksumTest, IsFnv1aOfTheCanonicalText) {
  const VehicleDescription birotor = BirotorDescription(BirotorParams{});
  const std::string text = DescriptionCanonicalText(birotor);
  EXPECT_EQ(DescriptionChecksum(birotor), TextChecksumHex(text));
  EXPECT_EQ(DescriptionChecksum(birotor).size(), 16u);
  // Version line first, reals in their shortest exact form, arm 1 at pi.
  EXPECT_EQ(text.rfind("vehicle_description_checksum: 1\nname: birotor\narm_count: 2\nbody_mass_kg: 4\n", 0), 0u)
      << text;
  EXPECT_NE(text.find("arms[0].angle_rad: 3.141592653589793\n"), std::string::npos) << text;
  EXPECT_NE(text.find("arms[1].spin: -1\n"), std::string::npos) << text;
  EXPECT_NE(text.find("arms[1].thrust_coeff_n_s2_rad2: 4.6e-05\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("arms[2]"), std::string::npos) << "unused arms are not part of it";
}

TEST(VehicleDescriptionChecksumTest, ReferenceBirotorValue) {
  // The reference birotor (BirotorParams defaults = config/reference_vehicle.yaml);
  // a change of this value means every log's description checksum changes:
  // bump kCanonicalTextVersion instead of editing the number.
  EXPECT_EQ(DescriptionChecksum(BirotorDescription(BirotorParams{})), "3c46c6d41f8659af");
}

TEST(VehicleDescriptionChecksumTest, UnusedArmsDoNotCount) {
  VehicleDescription a = BirotorDescription(BirotorParams{});
  VehicleDescription b = a;
  b.arms[4].stiffness_n_m_rad = 1.0;
  EXPECT_EQ(DescriptionChecksum(a), DescriptionChecksum(b));
}

TEST(VehicleDescriptionChecksumTest, EveryFieldChangesIt) {
  const VehicleDescription reference = BirotorDescription(BirotorParams{});
  const std::string reference_checksum = DescriptionChecksum(reference);
  // One change per field; reals by one unit in the last place.
  const auto ulp = [](double& x) { x = std::nextafter(x, INFINITY); };
  std::vector<std::function<void(VehicleDescription&)>> changes = {
      [](VehicleDescription& d) { d.name = "birotor2"; },
      [](VehicleDescription& d) { d.arm_count = 3; },
      [&](VehicleDescription& d) { ulp(d.body_mass_kg); },
      [&](VehicleDescription& d) { ulp(d.body_inertia_kg_m2); },
      [&](VehicleDescription& d) { ulp(d.gravity_m_s2); },
      [&](VehicleDescription& d) { ulp(d.omega_max_rad_s); },
      [&](VehicleDescription& d) { ulp(d.turbulence_std); },
      [&](VehicleDescription& d) { ulp(d.turbulence_corr_time_s); },
      [&](VehicleDescription& d) { ulp(d.gauge_offset_std_rad); },
      [&](VehicleDescription& d) { ulp(d.gauge_drift_psd_rad2_s); },
  };
  for (size_t arm = 0; arm < 2; ++arm) {
    changes.push_back([&, arm](VehicleDescription& d) { ulp(d.arms[arm].angle_rad); });
    changes.push_back([&, arm](VehicleDescription& d) { ulp(d.arms[arm].length_m); });
    changes.push_back([&, arm](VehicleDescription& d) { ulp(d.arms[arm].thrust_angle_rad); });
    changes.push_back([arm](VehicleDescription& d) { d.arms[arm].spin = -d.arms[arm].spin; });
    changes.push_back([&, arm](VehicleDescription& d) { ulp(d.arms[arm].stiffness_n_m_rad); });
    changes.push_back([&, arm](VehicleDescription& d) { ulp(d.arms[arm].damping_n_m_s_rad); });
    changes.push_back([&, arm](VehicleDescription& d) { ulp(d.arms[arm].tip_mass_kg); });
    changes.push_back([&, arm](VehicleDescription& d) { ulp(d.arms[arm].thrust_coeff_n_s2_rad2); });
    changes.push_back([&, arm](VehicleDescription& d) { ulp(d.arms[arm].motor_time_constant_s); });
    changes.push_back([arm](VehicleDescription& d) { d.arms[arm].has_gauge = !d.arms[arm].has_gauge; });
    changes.push_back([&, arm](VehicleDescription& d) { ulp(d.arms[arm].gauge_scale); });
    changes.push_back([&, arm](VehicleDescription& d) { ulp(d.arms[arm].gauge_offset_rad); });
  }
  std::vector<std::string> seen = {reference_checksum};
  for (size_t i = 0; i < changes.size(); ++i) {
    VehicleDescription changed = reference;
    changes[i](changed);
    const std::string checksum = DescriptionChecksum(changed);
    for (const std::string& other : seen) EXPECT_NE(checksum, other) << "change " << i;
    seen.push_back(checksum);
  }
}

}  // namespace
}  // namespace birotor
