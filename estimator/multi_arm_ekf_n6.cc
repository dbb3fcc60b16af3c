// The N-arm EKF and its model for N = 6 (one translation unit per N: see
// estimator/multi_arm_ekf_impl.h).
#include "estimator/multi_arm_ekf_impl.h"

namespace birotor {

template class MultiArmEkfModel<6>;
template class MultiArmEkf<6>;

}  // namespace birotor
