// MakeMultiArmEkf: the filter for the description's arm count. Each
// MultiArmEkf<N> is compiled in its own translation unit,
// estimator/multi_arm_ekf_n2.cc .. multi_arm_ekf_n6.cc.
#include "estimator/multi_arm_ekf.h"

namespace birotor {

std::unique_ptr<MultiArmForceEstimator> MakeMultiArmEkf(const VehicleDescription& vehicle, const EkfOptions& options) {
  switch (vehicle.arm_count) {
    case 2:
      return std::make_unique<MultiArmEkf<2>>(vehicle, options);
    case 3:
      return std::make_unique<MultiArmEkf<3>>(vehicle, options);
    case 4:
      return std::make_unique<MultiArmEkf<4>>(vehicle, options);
    case 5:
      return std::make_unique<MultiArmEkf<5>>(vehicle, options);
    case 6:
      return std::make_unique<MultiArmEkf<6>>(vehicle, options);
    default:
      return nullptr;
  }
}

}  // namespace birotor
