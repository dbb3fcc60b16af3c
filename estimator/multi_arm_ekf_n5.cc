// The N-arm EKF and its model for N = 5 (one translation unit per N: see
// estimator/multi_arm_ekf_impl.h).
#include "estimator/multi_arm_ekf_impl.h"

namespace birotor {

template class MultiArmEkfModel<5>;
template class MultiArmEkf<5>;

}  // namespace birotor
