// The N-arm EKF model instantiated once for every arm count 2 .. kMaxArms
// (the filter picks N from the description at start-up).
#include "estimator/multi_arm_ekf_model.h"

namespace birotor {

template class MultiArmEkfModel<2>;
template class MultiArmEkfModel<3>;
template class MultiArmEkfModel<4>;
template class MultiArmEkfModel<5>;
template class MultiArmEkfModel<6>;

}  // namespace birotor
