// The N-arm EKF and its model for N = 2 (one translation unit per N: see
// estimator/multi_arm_ekf_impl.h).
#include "estimator/multi_arm_ekf_impl.h"

namespace birotor {

template class MultiArmEkfModel<2>;
template class MultiArmEkf<2>;

}  // namespace birotor
